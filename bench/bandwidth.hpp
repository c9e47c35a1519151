#pragma once
// The bandwidth figures without sockets: a game of `players` moving players whose clients
// each receive every snapshot, full (BodyState) or delta, and acknowledge after a round trip.
#include <cstdint>

namespace arena::bench {

// One JSON line: bytes per snapshot per client, bodies in view, bytes per body (frames and
// the delta codec's payload), and the server's tick time: the world step plus that tick's share
// of the snapshots (delta clients are spread over the ticks between two snapshots).
void bench_bandwidth(uint32_t players, float view_radius, bool delta, uint32_t ticks);

// The same played as Asteroids ("rules": "asteroids") with every player firing whenever it
// may: the line also holds the game's bytes per snapshot (players' lines, names, events).
void bench_game_bandwidth(uint32_t players, float view_radius, uint32_t ticks);

}  // namespace arena::bench
