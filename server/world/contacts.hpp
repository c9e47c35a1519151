#pragma once
// Circle contacts: detection (circle–circle through the broadphase, circle–wall), impulse
// response with restitution, and positional correction so that resting bodies neither sink
// nor jitter.
#include <cstdint>
#include <span>
#include <vector>

#include "server/world/body.hpp"
#include "server/world/broadphase.hpp"
#include "server/world/config.hpp"

namespace arena::world {

enum class wall : int8_t { none = -1, left, right, bottom, top };

struct contact {
    uint32_t a = 0;  // body index
    uint32_t b = 0;  // body index; unused when `with` is a wall
    enum wall with = wall::none;
    vec2 normal{1, 0};        // unit, from a towards b (or towards the wall)
    real separation = 0;      // m, negative when overlapping
    real effective_mass = 0;  // kg, 1 / (1/m_a + 1/m_b)
    real bounce = 0;          // m/s, the least relative normal velocity allowed: the bounce, or
                              // −separation/Δt for a gap that may close this step
    real impulse = 0;         // N·s, accumulated normal impulse (never pulls)
};

// Every pair closer than the speculative distance and every body that near a wall, pairs first,
// in broadphase order.
void detect_contacts(std::span<const body> bodies, const world_config& config, broadphase_scratch& scratch,
                     std::vector<contact>& out);
// The same, on a grid the caller made (make_grid) from an extent it gathered on the way.
void detect_contacts(std::span<const body> bodies, const grid& g, const world_config& config,
                     broadphase_scratch& scratch, std::vector<contact>& out);

// Sequential impulses: each contact's relative normal velocity driven to its bounce target.
void solve_contact_velocities(std::span<body> bodies, std::span<contact> contacts, const world_config& config);

// Pushes overlapping bodies apart, beyond the slop, by mass share; velocities untouched.
void correct_penetration(std::span<body> bodies, std::span<const contact> contacts, const world_config& config);

// Each contact's accumulated impulse from the previous step, keyed by body ids, for warm
// starting. Part of the world's state: a world rebuilt from body states alone starts cold.
class impulse_cache {
public:
    // Sets each contact's impulse to the one it had last step (0 if new).
    void load(std::span<const body> bodies, std::span<contact> contacts) const;
    void store(std::span<const body> bodies, std::span<const contact> contacts);

private:
    struct entry {
        uint64_t key;
        real impulse;
    };
    std::vector<entry> entries_;  // sorted by key
};

}  // namespace arena::world
