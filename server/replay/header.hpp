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
