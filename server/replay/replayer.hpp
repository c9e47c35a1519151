#pragma once
// Re-simulates a recorded session offline: rebuilds the world from the header (config JSON and
// seed), applies every recorded tick with apply_tick (the server's own function) and compares
// every recorded hash. Stops at the first mismatch, the first file problem, the End record or
// the requested tick; a run stopped at the requested tick resumes from there on the next run
// (a player steps a recording a few ticks at a time).
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "protocol/result.hpp"
#include "server/replay/reader.hpp"
#include "server/rules/rules.hpp"
#include "server/world/world.hpp"

namespace arena::replay {

struct hash_mismatch {
    uint32_t tick = 0;
    uint64_t expected = 0;  // recorded
    uint64_t actual = 0;    // replayed
};

struct replay_options {
    // Stop when the world reaches this tick (after checking that tick's recorded hash, if any).
    std::optional<uint32_t> until;
    // Called with the start state's tick and hash, then after every step.
    std::function<void(uint32_t tick, uint64_t hash)> on_tick;
};

struct replay_report {
    uint32_t start_tick = 0;
    uint32_t final_tick = 0;  // the world's tick where the replay stopped
    uint64_t final_hash = 0;  // the world's hash there
    uint32_t ticks_replayed = 0;
    uint32_t hashes_checked = 0;            // the start hash, Hash records and the End record
    bool complete = false;                  // reached the End record, or `until`, with no problem
    std::optional<hash_mismatch> mismatch;  // the first one
    std::string error;                      // a file problem ("<file>: byte offset N: ...") or a bad `until`
};

class replayer {
public:
    // Opens and checks the file's header, builds the world and, when the recording started
    // after tick 0, advances it with empty ticks to the start tick (the start hash then tells
    // whether the recorded server had done the same).
    static protocol::result<std::unique_ptr<replayer>> open(const std::string& path);

    // Replays from the world's tick now: from the start on the first call, from where the last
    // run stopped at its `until` on a later one (a report then counts this run alone). After a
    // mismatch or a file problem a later run steps no further and reports that failure again.
    replay_report run(const replay_options& options = {});

    const header& file_header() const { return reader_.file_header(); }
    const world::world& state() const { return world_; }
    const rules::rules& game_rules() const { return *rules_; }
    // The name each of `lines`' players joined with, as the match's scoreboard names them ("" for
    // a player of a recording made before names were recorded).
    std::vector<std::string> scoreboard_names(std::span<const rules::score_line> lines) const;

private:
    replayer(reader r, const world::world_config& config, uint64_t seed);

    reader reader_;
    world::world world_;
    std::unique_ptr<rules::rules> rules_;
    bool start_checked_ = false;                 // the header's start hash, by the first run
    std::optional<match::tick_record> pending_;  // read by a run that stopped at its `until`
    bool ended_ = false;                         // the End record is read and checked
    std::optional<hash_mismatch> failed_hash_;   // the mismatch that stopped a run
    std::string failed_file_;                    // the file problem that stopped a run
    std::map<uint32_t, std::string> names_;      // player id -> the name it joined with
};

}  // namespace arena::replay
