#pragma once
// FNV-1a 64 over explicitly serialised fields (little-endian), never over struct bytes
// (padding would leak in). Floats are hashed by their bits: −0.0 and 0.0 differ, as they do in
// the state; NaN never enters the world.
#include <bit>
#include <cstdint>
#include <string_view>

#include "server/world/config.hpp"

namespace arena::world {

class fnv1a {
public:
    void add_u8(uint8_t v) {
        h_ ^= v;
        h_ *= 0x100000001b3ULL;
    }
    void add_u32(uint32_t v) {
        for (int i = 0; i < 4; ++i) add_u8(static_cast<uint8_t>(v >> (8 * i)));
    }
    void add_u64(uint64_t v) {
        for (int i = 0; i < 8; ++i) add_u8(static_cast<uint8_t>(v >> (8 * i)));
    }
    void add_real(float v) { add_u32(std::bit_cast<uint32_t>(v)); }
    void add_vec2(const vec2& v) {
        add_real(v.x());
        add_real(v.y());
    }
    void add_bytes(std::string_view s) {
        for (char c : s) add_u8(static_cast<uint8_t>(c));
    }
    uint64_t value() const { return h_; }

private:
    uint64_t h_ = 0xcbf29ce484222325ULL;
};

// Hash of every field of a config: two peers with the same hash run the same physics.
uint64_t config_hash(const world_config& config);

}  // namespace arena::world
