#pragma once
// A scripted multi-player session recorded through the real recorder and apply_tick, as the
// server records one: players join at different ticks (two in the same tick), two leave, and
// every player steers with inputs drawn from its own arena::world::rng, skipping some ticks
// as a jittery client would. The golden file's generator and the tests share it.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "protocol/result.hpp"
#include "server/replay/header.hpp"

namespace arena::replay::testing {

struct session_script {
    std::string preset = "asteroids";
    uint64_t world_seed = 20240501;
    uint64_t script_seed = 7;  // seeds the players' inputs
    uint32_t ticks = 600;
    uint32_t tick_rate = 60;
    uint32_t hash_interval = default_hash_interval;
    // Record a wrong hash (flipped low bit) for this world tick: a tampered recording.
    std::optional<uint32_t> alter_hash_at;
    // Leave the End record out, as a server killed mid-session would.
    bool finish = true;
};

struct session_result {
    uint32_t final_tick = 0;
    uint64_t final_hash = 0;
    std::vector<uint64_t> hashes;  // the world's hash at the start tick, then after every tick
};

// Records the session to `path`; the reason when the preset is unknown or a write fails.
protocol::result<session_result> record_scripted_session(const std::string& path, const session_script& script);

}  // namespace arena::replay::testing
