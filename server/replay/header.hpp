#pragma once
// What a replay file says about its session before the first tick: enough to rebuild the
// world exactly (versions, config, seed, start tick) and to check that it was rebuilt right
// (the start hash).
#include <cstdint>
#include <string>

#include "protocol/version.hpp"
#include "server/world/world.hpp"

namespace arena::replay {

// Layout of replay files this build writes and the highest it reads. Bump it for any change
// an older reader could not replay correctly (see protocol/replay.fbs).
inline constexpr uint32_t current_format_version = 1;

// A Hash record every this many ticks unless the recording says otherwise (1 s at 60 Hz).
inline constexpr uint32_t default_hash_interval = 60;

// What arena-server can record, so that a file from a stranger cannot ask for more work than a
// real recording would. The reader refuses a file beyond any of these (byte offset and reason).
// arena-server's --tick-rate range.
inline constexpr uint32_t max_tick_rate = 1000;
// arena-server's --hash-interval range.
inline constexpr uint32_t max_hash_interval = 1'000'000;
// The server records from its first tick (start_tick 0); a recording that starts later is
// replayed by stepping an empty world up to start_tick first, and that is allowed for at most
// a minute of ticks (a start_tick of 0xFFFFFFFF asked for 4.3 billion steps before any check).
inline constexpr uint32_t max_start_seconds = 60;
// arena-server's --max-players range: no tick can have more joins.
inline constexpr uint32_t max_joins_per_tick = 100'000;

// The world steps replaying a file costs at most: the empty steps up to start_tick, then one
// per Tick record (each at least min_record_bytes of the file).
inline constexpr uint64_t max_start_tick(uint32_t tick_rate) {
    return uint64_t{max_start_seconds} * tick_rate;
}

struct header {
    uint32_t format_version = current_format_version;  // leave as is; tests write others
    uint16_t protocol_version = protocol::protocol_version;
    uint32_t world_version = world::world_version;
    std::string world_config;  // JSON, arena::config::config_to_json
    std::string preset;        // for people reading the file; the JSON is what counts
    uint64_t seed = 0;
    uint32_t tick_rate = 60;                         // ticks per second, > 0
    uint32_t hash_interval = default_hash_interval;  // ticks, > 0
    uint32_t start_tick = 0;                         // the world's tick when recording started
    uint64_t start_hash = 0;                         // the world's hash at start_tick
};

// The header of a recording of `w` starting now: its config, tick and hash, and the seed and
// preset it was built from.
header make_header(const world::world& w, std::string preset, uint64_t seed, uint32_t tick_rate,
                   uint32_t hash_interval = default_hash_interval);

}  // namespace arena::replay
