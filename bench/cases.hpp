#pragma once
// The benchmark cases of arena-bench; each prints one JSON line per measurement.
#include <cstdint>
#include <string>

#include "server/world/config.hpp"

namespace arena::bench {

// The asteroids preset grown to `bodies` rocks at the preset's crowding, as
// `arena-sim --preset asteroids --bodies N` grows it: the side scales with √(N / 40).
world::world_config scaled_asteroids(uint32_t bodies);

void bench_world_step(uint32_t bodies, int warmup, int steps);
void bench_integration(uint32_t bodies, int samples);
void bench_snapshot(uint32_t bodies, uint32_t clients, int samples);
// Records a `players`-player asteroids session of `ticks` ticks to `path`, then replays it.
bool bench_replay(uint32_t players, uint32_t ticks, const std::string& path);

}  // namespace arena::bench
