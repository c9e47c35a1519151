#pragma once
// A recording played a few ticks at a time, for a player with play, pause and a scrub bar:
// the replayer (server/replay) steps the world and checks every recorded hash; this keeps
// where it is, the hash it computed there, and how many recorded hashes matched so far.
// Seeking back starts over from the recording's start and re-simulates (a recording is
// minutes long at most, and the world steps far faster than real time).
//
// It also keeps what a viewer reads beside the bodies: the game's manifest, and a log of the
// game's declared events as the replayed rules raised them, each with its tick. The log holds
// the newest max_logged_events; a seek back re-simulates, so it is rebuilt with the world.
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "protocol/manifest.hpp"
#include "protocol/result.hpp"
#include "server/replay/replayer.hpp"

namespace arena::sdk {

class replay_player {
public:
    // Reads the whole file once without simulating (the reader's checks, the last tick and
    // every recorded hash), then opens it for playing at its start tick. A file without its
    // End (still being recorded, or cut short by a crash) plays up to its last complete Tick
    // record; cut_short() says what was wrong after it.
    static protocol::result<std::unique_ptr<replay_player>> open(const std::string& path);

    // Plays up to `ticks` ticks on, never past the end. False when a hash mismatched or the
    // file has a problem (error() says which); the player then stays where that happened.
    bool step(uint32_t ticks);
    // Goes to `tick` (clamped to the recording's start and end): on from here, or from the start.
    bool seek(uint32_t tick);

    uint32_t tick() const { return replayer_->state().tick(); }
    uint32_t start_tick() const { return start_tick_; }
    uint32_t end_tick() const { return end_tick_; }
    // The hash computed at tick() (the world's at the start, then the world's and the rules').
    uint64_t hash() const { return hash_; }
    // The hash the recording holds for tick(), when it holds one.
    std::optional<uint64_t> recorded_hash() const;
    // Recorded hashes compared since the start (each one matched, but a mismatch), and how
    // many the file holds (the start hash, every Hash record and the End).
    uint32_t hashes_checked() const { return hashes_checked_; }
    uint32_t hashes_total() const { return static_cast<uint32_t>(recorded_.size()); }
    const std::optional<replay::hash_mismatch>& mismatch() const { return mismatch_; }
    const std::string& error() const { return error_; }
    const std::string& cut_short() const { return cut_short_; }

    const replay::header& file_header() const { return replayer_->file_header(); }
    const world::world& world() const { return replayer_->state(); }
    const rules::rules& game_rules() const { return replayer_->game_rules(); }
    // The name each of `lines`' players joined with ("" when the recording holds none).
    std::vector<std::string> names_of(std::span<const rules::score_line> lines) const {
        return replayer_->scoreboard_names(lines);
    }
    // The name player `id` joined with, up to tick(): also of a player who has left since, as an
    // event may name one ("" when the recording holds none).
    std::string name_of(uint32_t id) const;

    // What the replayed game declares of itself (empty for the sandbox), asked of the rules once
    // per start, as the match asks once per match.
    const protocol::game_manifest& manifest() const { return manifest_; }

    // One of the game's declared events, with the tick the step that raised it made, and its
    // number since the start (1 for the first), so that a viewer can tell new ones.
    struct logged_event {
        uint32_t sequence = 0;
        uint32_t tick = 0;
        rules::declared_event event;
    };
    // The newest events up to tick(), oldest first: at most max_logged_events (a long match
    // raises thousands; a viewer shows the last few).
    static constexpr size_t max_logged_events = 64;
    const std::deque<logged_event>& events() const { return events_; }

private:
    struct recorded_hash_at {
        uint32_t tick;
        uint64_t hash;
    };
    replay_player() = default;
    bool restart();
    bool run_until(uint32_t tick);

    std::string path_;
    std::unique_ptr<replay::replayer> replayer_;
    uint32_t start_tick_ = 0;
    uint32_t end_tick_ = 0;
    std::vector<recorded_hash_at> recorded_;  // by tick: the start hash, Hash records, the End
    uint64_t hash_ = 0;
    uint32_t hashes_checked_ = 0;
    std::optional<replay::hash_mismatch> mismatch_;
    std::string error_;
    std::string cut_short_;
    protocol::game_manifest manifest_;
    std::deque<logged_event> events_;
    uint32_t events_seen_ = 0;  // since the start: the next event's sequence - 1
};

}  // namespace arena::sdk
