#pragma once
// Collision filtering, as Box2D's b2Filter: each body has category bits (what it is) and mask
// bits (what it collides with), and two bodies collide only when each one's category is in
// the other's mask. A group overrides both: bodies of the same non-zero group always collide
// when it is positive and never when it is negative (a ship and its own bullets). The default
// collides with everything, so worlds that never set a filter behave as before filters existed.
#include <cstdint>

namespace arena::world {

struct collision_filter {
    uint32_t category = 1;  // what the body is: usually one bit
    uint32_t mask = ~0u;    // the categories it collides with; 0: it passes through every body
    int32_t group = 0;      // 0: none; same positive group: always; same negative group: never

    bool is_default() const { return category == 1 && mask == ~0u && group == 0; }
};

inline bool should_collide(const collision_filter& a, const collision_filter& b) {
    if (a.group == b.group && a.group != 0) return a.group > 0;
    return (a.category & b.mask) != 0 && (b.category & a.mask) != 0;
}

}  // namespace arena::world
