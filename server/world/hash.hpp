#pragma once
// The world's hashes: FNV-1a 64 (fnv1a.hpp) over explicitly serialised fields, never over
// struct bytes (padding would leak in). Floats are hashed by their bits: −0.0 and 0.0 differ,
// as they do in the state; NaN never enters the world.
#include <cstdint>

#include "server/world/config.hpp"
#include "server/world/fnv1a.hpp"

namespace arena::world {

// FNV-1a 64 that also takes the world's scalars and vectors.
class fnv1a : public fnv1a_64 {
public:
    void add_real(real v) { add_f32(v); }
    void add_vec2(const vec2& v) {
        add_real(v.x());
        add_real(v.y());
    }
};

// Hash of every field of a config: two peers with the same hash run the same physics.
uint64_t config_hash(const world_config& config);

}  // namespace arena::world
