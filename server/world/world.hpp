#pragma once
// The deterministic world: a pure function of (config, seed, inputs per tick). No clocks,
// threads or I/O in here; Δt is the config's constant and time advances only through step().
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "server/world/body.hpp"
#include "server/world/config.hpp"
#include "server/world/contact_events.hpp"
#include "server/world/contacts.hpp"
#include "server/world/input.hpp"
#include "server/world/profile.hpp"
#include "server/world/rng.hpp"
#include "server/world/shape.hpp"
#include "server/world/soft_solver.hpp"
#include "server/world/solver.hpp"
#include "server/world/static_index.hpp"

namespace arena::world {

// Version of the world's physics: bump when a change alters results on purpose, so that
// recordings and clients from another version are recognised (version.hpp says which older
// recordings still replay).
// 2: shapes (capsules, polygons, segments), contact friction and rotation at contacts.
// 3: a chain's segments know their neighbours (ghost vertices) and collide on one side.
// 4: the sub-stepped solver (substeps > 1) solves its contacts colour by colour, several at once.
inline constexpr uint32_t world_version = 4;

class world {
public:
    // A world with the config's rocks spawned from `seed`.
    world(const world_config& config, uint64_t seed);

    // Bodies may be added and removed between steps (game rules spawn bullets and split rocks);
    // an id the world assigned is never assigned again, even after its body is removed.
    // Adds a body; its id is assigned when b.id == 0, else b.id is used (it must be unused).
    // Returns the id, or nothing when the world is full or the id is taken.
    std::optional<uint32_t> add_body(body b);
    // The same for a body of shape `s` (make_body(material, s, position) gives its mass). A
    // body with zero inverse mass is static: level geometry, kept out of the moving bodies' grid.
    std::optional<uint32_t> add_body(body b, const shape& s);
    // A chain of static segments through `points` (one body each), made of `material`'s
    // friction and restitution. Returns the ids, or nothing when the world is full or two
    // consecutive points are equal (nothing is added then). Each
    // segment knows its neighbours (shape::chain), so that bodies slide across the joints, and
    // is solid on the left of the chain's direction only (a floor runs left to right); a chain
    // of 4 or more points whose last point is its first is a closed loop, and so is one of 3 or
    // more in a wrapping world whose last point is its first one world size on (round the world).
    std::optional<std::vector<uint32_t>> add_chain(std::span<const vec2> points, const body_material& material);
    // A player's body of the config's player material at a free spot drawn from the world's rng.
    std::optional<body_id> spawn_player(player_id owner);
    // spawn_player for each owner in order, with the same results, in O(bodies + owners) tests
    // rather than O(bodies × owners). Each entry is the body's id, or none (0) when the world is
    // full.
    std::vector<body_id> spawn_players(std::span<const player_id> owners);
    bool remove_body(uint32_t id);
    // remove_body for each id (unknown ids ignored), with the same result, in one pass over the
    // bodies: one erase per id moved the tail each time (quadratic for a tick of many leaves).
    void remove_bodies(std::span<const body_id> ids);

    body* find(uint32_t id);
    const body* find(uint32_t id) const;
    body* find(body_id id) { return find(id.value()); }
    const body* find(body_id id) const { return find(id.value()); }
    std::span<const body> bodies() const { return bodies_; }
    std::span<body> bodies() { return bodies_; }
    // The shape of `b` (one of this world's bodies): its own, or a circle of its radius.
    shape shape_of(const body& b) const;

    // Advances one fixed Δt (in config().substeps sub-steps when more than 1, see
    // soft_solver.hpp). Inputs must have passed check_input (asserted; they are clamped here);
    // inputs for unknown bodies are ignored.
    void step(const tick_inputs& inputs);

    // 64-bit FNV-1a of the tick, the rng and every body's fields, in id order.
    uint64_t hash() const;

    uint32_t tick() const { return tick_; }
    const world_config& config() const { return config_; }
    // Contacts found in the last step (for tests and tools).
    std::span<const contact> last_contacts() const { return contacts_; }
    // Contact events (contact_events.hpp): off by default (they cost a pass over the contacts);
    // game rules turn them on. They never change the state, so the hash ignores them.
    void set_contact_events(bool on);
    bool contact_events_on() const { return events_on_; }
    // The pairs that began touching in the last step, sorted by (a, b); empty when off.
    std::span<const contact_event> contact_events() const { return events_.events(); }
    // True when `b` rests on or touches the floor, or stood on another body in the last step.
    bool on_ground(const body& b) const;

    // Per-phase timing of step() (profile.hpp): from now on every step adds to profile(), read
    // through `timer`; a default step_timer turns it off. The results never depend on it.
    void set_step_timer(const step_timer& timer) { timer_ = timer; }
    const step_profile& profile() const { return profile_; }
    void reset_profile() { profile_ = {}; }

private:
    void apply_inputs(const tick_inputs& inputs);
    void apply_input(const body_input& in);  // one body's, if the body is still there
    // The middle of step(), from forces to the position pass: one of them per step.
    void step_one_pass(phase_laps& laps);    // config_.substeps == 1
    void step_substepped(phase_laps& laps);  // config_.substeps > 1
    body_extent integrate_velocities();      // forces, velocities (and explicit Euler's positions)
    body_extent accumulate_all_forces();     // forces only (the sub-stepped solver integrates)
    void detect_collisions(const body_extent& extent);
    void integrate_positions();  // positions, clearing, wrapping of bodies in no contact
    void wrap_touched_bodies();  // wrapping of the bodies in contacts
    void place_bodies();         // the config's bodies
    void spawn_rocks();
    std::optional<shape> irregular_polygon(real radius);
    void note_supported();  // the bodies with an owner that stand on something, for on_ground
    // A spot in [r, size − r]² that overlaps nobody `is_free` knows of (a few tries; a crowded
    // world takes the last try).
    template <class IsFree>
    vec2 random_free_position(real radius, IsFree is_free);

    world_config config_;
    rng rng_;
    std::vector<body> bodies_;           // sorted by id
    std::vector<shape> shapes_;          // the pool body::shape indexes
    std::vector<uint32_t> free_shapes_;  // pool entries of removed bodies, reused last-in first-out
    uint32_t next_id_ = 1;
    uint32_t tick_ = 0;
    std::vector<contact> contacts_;
    broadphase_scratch scratch_;
    std::vector<uint8_t> touched_;  // body index → in a contact this step (wrap worlds only)
    impulse_cache impulses_;
    contact_solver solver_;
    soft_contact_solver soft_solver_;  // config_.substeps > 1
    static_index statics_;
    bool statics_dirty_ = true;  // bodies added or removed since statics_ was built
    std::vector<uint32_t> query_scratch_;
    std::vector<uint32_t> supported_;  // ids, increasing (see note_supported)
    step_timer timer_;
    step_profile profile_;
    bool events_on_ = false;
    contact_event_tracker events_;
};

}  // namespace arena::world
