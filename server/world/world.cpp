#include "server/world/world.hpp"

#include <algorithm>

#include "server/world/assert.hpp"
#include "server/world/forces.hpp"
#include "server/world/hash.hpp"
#include "server/world/integrate.hpp"

namespace arena::world {

world::world(const world_config& config, uint64_t seed) : config_(config), rng_(seed) {
    place_bodies();
    spawn_rocks();
}

void world::step(const tick_inputs& inputs) {
    // The broadphase's lap is taken inside detection, once the bodies are bucketed.
    phase_laps laps(timer_, profile_);
    scratch_.laps = timer_.now_ns ? &laps : nullptr;
    apply_inputs(inputs);
    laps.lap(step_phase::inputs);
    if (config_.substeps > 1)
        step_substepped(laps);
    else
        step_one_pass(laps);
    note_supported();
    laps.lap(step_phase::correction);
    laps.finish();
    scratch_.laps = nullptr;
    ++tick_;
}

// Velocities, detection, one solve, positions, then a position correction.
void world::step_one_pass(phase_laps& laps) {
    const body_extent extent = integrate_velocities();
    laps.lap(step_phase::forces_velocities);
    detect_collisions(extent);
    laps.lap(step_phase::narrow_phase);
    impulses_.load(bodies_, contacts_);
    if (events_on_) events_.measure_approach(bodies_, contacts_);
    solver_.solve_velocities(bodies_, contacts_, config_);
    if (events_on_) events_.collect(bodies_, contacts_);
    impulses_.store(bodies_, contacts_);
    laps.lap(step_phase::solver);
    integrate_positions();
    laps.lap(step_phase::positions);
    solver_.correct_positions(bodies_, contacts_, config_);
    wrap_touched_bodies();
}

// Box2D v3's soft step: forces, detection, then the sub-steps (soft_solver.hpp), which integrate
// velocities and positions themselves; accumulators cleared and every body wrapped after them.
void world::step_substepped(phase_laps& laps) {
    const body_extent extent = accumulate_all_forces();
    laps.lap(step_phase::forces_velocities);
    detect_collisions(extent);
    laps.lap(step_phase::narrow_phase);
    impulses_.load(bodies_, contacts_);
    if (events_on_) events_.measure_approach(bodies_, contacts_);
    soft_solver_.step(bodies_, contacts_, config_);
    if (events_on_) events_.collect(bodies_, contacts_, true);
    impulses_.store(bodies_, contacts_);
    laps.lap(step_phase::solver);
    for (body& b : bodies_) {
        clear_accumulators(b);
        wrap_position(b, config_);
    }
    laps.lap(step_phase::positions);
}

void world::apply_inputs(const tick_inputs& inputs) {
    // In body id order, whatever order the caller listed them in. A match lists them by
    // player, mostly body order already: then they are applied as they are, with no copy and
    // no sort (a stable sort of a sorted list keeps it as it is: the same order either way).
    const auto by_body = [](const body_input& l, const body_input& r) {
        return l.body_id < r.body_id;
    };
    if (std::is_sorted(inputs.begin(), inputs.end(), by_body)) {
        for (const body_input& in : inputs) apply_input(in);
        return;
    }
    std::vector<const body_input*> ordered;
    ordered.reserve(inputs.size());
    for (const body_input& in : inputs) ordered.push_back(&in);
    std::stable_sort(ordered.begin(), ordered.end(),
                     [&](const body_input* l, const body_input* r) { return by_body(*l, *r); });
    for (const body_input* in : ordered) apply_input(*in);
}

void world::apply_input(const body_input& in) {
    body* b = find(in.body_id);
    if (!b) return;
    // Non-finite inputs are refused where they enter: admission for the network, the
    // replay reader for files. Clamped here, a NaN would stay NaN and spread.
    ARENA_ASSERT(!check_input(in.input), "an input reached the world without passing check_input");
    apply_player_input(*b, clamp_input(in.input), config_.control, on_ground(*b));
}

// Forces and velocities in one pass: a body's forces depend only on that body, so fusing the
// phases changes no result, and the body array is streamed once instead of three times.
// The same pass gathers the extent the broadphase's grid needs (positions do not change again
// before detection).
body_extent world::integrate_velocities() {
    const real dt = config_.dt;
    body_extent extent;
    for (body& b : bodies_) {
        accumulate_forces(b, config_);
        if (config_.integrator == integrator::explicit_euler) integrate_position(b, dt);  // old velocity
        integrate_velocity(b, dt);
        if (!b.is_static()) extent.add(b);
    }
    return extent;
}

body_extent world::accumulate_all_forces() {
    body_extent extent;
    for (body& b : bodies_) {
        accumulate_forces(b, config_);
        if (!b.is_static()) extent.add(b);
    }
    return extent;
}

void world::detect_collisions(const body_extent& extent) {
    if (statics_dirty_) {
        statics_.build(bodies_, shapes_, config_);
        statics_dirty_ = false;
    }
    detect_contacts({bodies_, shapes_, &statics_}, make_grid(extent, bodies_.size(), config_), config_, scratch_,
                    query_scratch_, contacts_);
    if (config_.boundary != boundary::wrap) return;
    // Bodies in a contact may still be pushed by correct_penetration: they wrap after it.
    touched_.assign(bodies_.size(), 0);
    for (const contact& c : contacts_) {
        touched_[c.a] = 1;
        if (c.with == wall::none) touched_[c.b] = 1;
    }
}

// Positions (semi-implicit Euler, with the velocity after the contacts), accumulators cleared
// and, for bodies in no contact, wrapping, in one pass. Each is per body and a body in no
// contact is not moved again this step, so the results are those of separate passes.
void world::integrate_positions() {
    const real dt = config_.dt;
    const bool semi_implicit = config_.integrator == integrator::semi_implicit;
    const bool wraps = config_.boundary == boundary::wrap;
    for (size_t i = 0; i < bodies_.size(); ++i) {
        body& b = bodies_[i];
        if (semi_implicit) integrate_position(b, dt);
        clear_accumulators(b);
        if (wraps && !touched_[i]) wrap_position(b, config_);
    }
}

// The bodies that correct_penetration may have moved, wrapped after it (wrapping is idempotent,
// so a body in several contacts is wrapped once in effect).
void world::wrap_touched_bodies() {
    if (config_.boundary != boundary::wrap) return;
    for (const contact& c : contacts_) {
        wrap_position(bodies_[c.a], config_);
        if (c.with == wall::none) wrap_position(bodies_[c.b], config_);
    }
}

void world::set_contact_events(bool on) {
    if (on == events_on_) return;
    events_on_ = on;
    events_.reset();
}

bool world::on_ground(const body& b) const {
    return touches_floor(b, config_) || std::binary_search(supported_.begin(), supported_.end(), b.id);
}

// A body stands on what it touches below it: a contact whose normal points down from it by more
// than 45° (cos 45° ≈ 0.707), at most the slop apart. Only bodies with an owner are listed:
// jumping needs it, nothing else does.
void world::note_supported() {
    supported_.clear();
    const real down = -0.70710678f;
    for (const contact& c : contacts_) {
        if (c.separation > config_.penetration_slop) continue;
        if (c.normal.y() < down && bodies_[c.a].owner != 0) supported_.push_back(bodies_[c.a].id);
        if (c.with == wall::none && -c.normal.y() < down && bodies_[c.b].owner != 0)
            supported_.push_back(bodies_[c.b].id);
    }
    // Ids are integers: sorting them is a total order.
    std::sort(supported_.begin(), supported_.end());
}

shape world::shape_of(const body& b) const {
    return b.shape == no_shape ? make_circle(b.radius) : shapes_[b.shape];
}

uint64_t world::hash() const {
    fnv1a h;
    h.add_u32(tick_);
    h.add_u64(rng_.state());
    h.add_u32(static_cast<uint32_t>(bodies_.size()));
    for (const body& b : bodies_) {
        h.add_u32(b.id);
        h.add_u32(b.owner);
        h.add_real(b.mass);
        h.add_real(b.inv_mass);
        h.add_real(b.inertia);
        h.add_real(b.inv_inertia);
        h.add_real(b.radius);
        h.add_real(b.restitution);
        h.add_real(b.friction);
        h.add_u8(static_cast<uint8_t>(b.shape == no_shape ? shape_kind::circle : shapes_[b.shape].kind));
        h.add_real(b.drag_area);
        h.add_vec2(b.position);
        h.add_vec2(b.velocity);
        h.add_real(b.angle);
        h.add_real(b.angular_velocity);
        h.add_u32(b.impulse_cooldown);
        // Only a filter someone set: a world that never sets one keeps the hashes it had
        // before filters existed (the golden hashes), and one that does still hashes them all.
        if (!b.filter.is_default()) {
            h.add_u8(0xf1);
            h.add_u32(b.filter.category);
            h.add_u32(b.filter.mask);
            h.add_u32(static_cast<uint32_t>(b.filter.group));
        }
    }
    return h.value();
}

}  // namespace arena::world
