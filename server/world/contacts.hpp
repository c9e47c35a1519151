#pragma once
// Contacts: detection (broadphase pairs and static bodies through the narrow phase, bodies
// near the walls), then the solver (solver.hpp) drives them.
//
// Mixing rules, per contact (Box2D's): friction μ = √(μa·μb), so that either surface can make a
// contact slippery (ice); restitution e = max(ea, eb), so that anything bounces off a trampoline.
// A wall has the world's floor_friction as its μ and no restitution of its own.
#include <cstdint>
#include <span>
#include <vector>

#include "server/world/body.hpp"
#include "server/world/broadphase.hpp"
#include "server/world/config.hpp"
#include "server/world/static_index.hpp"

namespace arena::world {

enum class wall : int8_t { none = -1, left, right, bottom, top };

struct contact_point {
    vec2 anchor_a{0, 0};       // m, from a's centre to the point (world frame, at detection)
    vec2 anchor_b{0, 0};       // m, from b's centre to the point (unused for a wall)
    real separation = 0;       // m, negative when overlapping
    real normal_impulse = 0;   // N·s, accumulated (never pulls)
    real tangent_impulse = 0;  // N·s, accumulated, |·| ≤ μ·normal_impulse
    real normal_mass = 0;      // kg, 1 / (the normal's effective inverse mass at this point)
    real tangent_mass = 0;     // kg, the same along the tangent
    real bounce = 0;           // m/s, the least relative normal velocity allowed: the bounce, or
                               // −separation/Δt for a gap that may close this step
    real rn_a = 0, rn_b = 0;   // m, anchor × normal for a and b (the solver's lever arms)
    real rt_a = 0, rt_b = 0;   // m, anchor × tangent
    real step_impulse = 0;     // N·s, the normal impulse applied over the whole step, summed over
                               // its sub-steps (the sub-stepped solver only, soft_solver.hpp)
    uint16_t id = 0;           // feature id (manifold.hpp): the key for warm starting
};

struct contact {
    uint32_t a = 0;  // body index
    uint32_t b = 0;  // body index; unused when `with` is a wall
    enum wall with = wall::none;
    uint8_t count = 0;     // points, 1 or 2
    vec2 normal{1, 0};     // unit, from a towards b (or towards the wall)
    real separation = 0;   // m, the least of its points' separations
    real friction = 0;     // μ, mixed
    real restitution = 0;  // e, mixed
    uint32_t slot_a = 0;   // the solver's body slots (0: a static body or a wall)
    uint32_t slot_b = 0;
    contact_point points[2];  // the first `count` are used
};

// What detection reads besides the config: the bodies, the shapes of those that are not
// circles, and the static bodies' index.
struct collision_scene {
    std::span<const body> bodies;
    std::span<const shape> pool;
    const static_index* statics = nullptr;  // nullptr: static bodies are in the grid like the others
};

// Every pair closer than the speculative distance, every body that near a static body or a wall:
// dynamic pairs first in broadphase order, then static pairs and walls in body index order.
void detect_contacts(const collision_scene& scene, const grid& g, const world_config& config,
                     broadphase_scratch& scratch, std::vector<uint32_t>& query_scratch, std::vector<contact>& out);
// Circles only, no static index (tests and tools).
void detect_contacts(std::span<const body> bodies, const world_config& config, broadphase_scratch& scratch,
                     std::vector<contact>& out);

// Each contact point's accumulated impulses from the previous step, keyed by the body ids and
// the point's feature id, for warm starting. Part of the world's state: a world rebuilt from
// body states alone starts cold.
class impulse_cache {
public:
    // Sets each point's impulses to those it had last step (0 if new).
    void load(std::span<const body> bodies, std::span<contact> contacts);
    void store(std::span<const body> bodies, std::span<const contact> contacts);

private:
    struct entry {
        uint64_t key;
        uint16_t id[2];
        uint8_t count;
        real normal[2];
        real tangent[2];
    };
    // The entry of `key`, or nullptr.
    const entry* find(uint64_t key);
    void build_table();

    std::vector<entry> entries_;  // in contact order
    // Open addressing over entries_ (entry number + 1, 0 = empty), a power of two at least twice
    // as large; empty until a lookup needs it. Only looked up, never iterated, so its order
    // cannot leak into the results; it replaced a sort of the entries, a tenth of a pyramid's
    // step.
    std::vector<uint32_t> table_;
};

}  // namespace arena::world
