#pragma once
// A recording played a few ticks at a time, for a player with play, pause and a scrub bar:
// the replayer (server/replay) steps the world and checks every recorded hash; this keeps
// where it is, the hash it computed there, and how many recorded hashes matched so far.
// Seeking back starts over from the recording's start and re-simulates (a recording is
// minutes long at most, and the world steps far faster than real time).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

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
};

}  // namespace arena::sdk
