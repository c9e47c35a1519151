#pragma once
// Writes a replay file while a session runs. No threads and no Asio: the server's tick loop
// calls it once per tick. Records are buffered in memory and written at least once per second
// of ticks (tick_rate ticks), so a crash loses at most the last second; finish() writes the
// End record and flushes, and the destructor flushes whatever it still holds (a file without
// End replays up to its last complete record and is reported as cut short).
//
// Use:
//   auto opened = recorder::open(path, make_header(world, preset, seed, tick_rate));
//   each tick:  apply_tick(world, record); rec.record_tick(record, world.hash());
//   shutdown:   rec.finish(world.tick(), world.hash());
#include <cstdint>
#include <string>
#include <vector>

#include "protocol/result.hpp"
#include "server/match/tick_record.hpp"
#include "server/replay/file_handle.hpp"
#include "server/replay/header.hpp"
#include "server/replay/record_format.hpp"
#include "server/replay/status.hpp"

namespace arena::replay {

class recorder {
public:
    // Creates (or truncates) `path` and writes the header at once, so that even a session that
    // dies in its first second leaves a file that names its config and seed.
    static protocol::result<recorder> open(const std::string& path, const header& h);

    recorder() = default;  // closed: every call fails; for result<recorder>
    recorder(recorder&& other) noexcept;
    recorder& operator=(recorder&& other) noexcept;
    recorder(const recorder&) = delete;
    recorder& operator=(const recorder&) = delete;
    ~recorder();

    // Records one applied tick: `record` exactly as passed to apply_tick, and the world's hash
    // after that step (world.hash()); a Hash record follows when the new tick is a multiple of
    // the header's hash_interval. Ticks must come one after another from the header's
    // start_tick (record.tick == the world's tick before the step); a gap is refused and
    // nothing is written. After a write error every call returns that error.
    status record_tick(const match::tick_record& record, uint64_t hash_after_step);

    // Writes the End record (the world's tick and hash now), flushes and closes the file.
    status finish(uint32_t final_tick, uint64_t final_hash);

    // Writes buffered records to the OS now.
    status flush();

    bool is_open() const { return file_ != nullptr; }
    const std::string& path() const { return path_; }
    // The tick the next record_tick must carry.
    uint32_t next_tick() const { return next_tick_; }

private:
    void flush_quietly() noexcept;

    std::string path_;
    file_handle file_;
    record_encoder encoder_;
    std::vector<uint8_t> buffer_;  // whole records not yet written
    uint32_t next_tick_ = 0;
    uint32_t tick_rate_ = 1;
    uint32_t hash_interval_ = default_hash_interval;
    uint32_t ticks_since_flush_ = 0;
    std::string error_;  // the first write error; sticky
};

}  // namespace arena::replay
