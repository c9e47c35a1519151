#pragma once
// The forces of the lecture, accumulated into a body for one step: weight, thrust and torque
// from a player's input, the floor's normal force and kinetic friction, and quadratic drag.
// The per-body forces are defined here, inline: they run for every body every step, fused with
// the integration into one pass over the bodies (world.cpp), and a call into another
// translation unit per force was a quarter of the integration's time.
#include <cmath>

#include "server/world/body.hpp"
#include "server/world/config.hpp"
#include "server/world/input.hpp"

namespace arena::world {

// Thrust along the facing (or +x), torque, and the button-0 impulse if its cooldown allows.
void apply_player_input(body& b, const player_input& input, const control_config& control, bool on_ground);

// Weight m·g.
inline void apply_weight(body& b, const vec2& gravity) {
    if (!b.is_static()) b.apply_force(gravity * b.mass);
}

// On the floor: the normal force N = m·max(0, −g_y) cancels the weight's downward part, and
// kinetic friction −μ·N·sign(vx) opposes sliding (as resistance: it stops, never reverses).
inline void apply_floor_contact(body& b, const vec2& gravity, real friction) {
    // A body moving away from the floor (a jump) feels neither its push nor its friction.
    if (b.is_static() || gravity.y() >= 0 || b.velocity.y() > 0) return;
    const real normal = b.mass * -gravity.y();  // N
    b.apply_force(vec2{0, normal});
    if (b.velocity.x() != 0) b.resistance.x() -= friction * normal * (b.velocity.x() > 0 ? 1.0f : -1.0f);
}

// Quadratic drag −½·ρ·|v|²·(A·Cd)·v̂ in a medium of density `rho` (as resistance).
inline void apply_drag(body& b, real rho) {
    if (b.drag_area == 0 || rho == 0) return;
    const real speed_sq = b.velocity.squaredNorm();
    if (speed_sq == 0) return;
    // −½ρ|v|²·ACd·v̂ = −½ρ|v|·ACd·v: one sqrt instead of a normalisation.
    const real speed = std::sqrt(speed_sq);
    b.resistance -= b.velocity * (0.5f * rho * b.drag_area * speed);
}

// −damping·I·ω (as resistance torque).
inline void apply_angular_damping(body& b, real damping) {
    if (damping == 0 || b.inv_inertia == 0) return;
    b.resistance_torque -= damping * b.inertia * b.angular_velocity;
}

// Density of the medium at `position`: the first fluid region containing it, else the air.
inline real medium_density(const world_config& config, const vec2& position) {
    for (const fluid_region& f : config.fluids) {
        if (position.x() >= f.min.x() && position.x() <= f.max.x() && position.y() >= f.min.y() &&
            position.y() <= f.max.y())
            return f.density;
    }
    return config.air_density;
}

// True when `b`, a circle, rests on or touches the floor (within the penetration slop). The
// lecture's floor model is for circles (players, balls); other shapes meet the floor through
// contacts with friction (contacts.hpp).
inline bool touches_floor(const body& b, const world_config& config) {
    if (config.boundary != boundary::walls && config.boundary != boundary::floor) return false;
    return b.shape == no_shape && b.position.y() - b.radius <= config.penetration_slop;
}

// Every force of the environment on `b` for this step, in this order: weight, the floor's
// push and friction, drag, angular damping.
inline void accumulate_forces(body& b, const world_config& config) {
    apply_weight(b, config.gravity);
    if (touches_floor(b, config)) apply_floor_contact(b, config.gravity, config.floor_friction);
    if (b.drag_area != 0) apply_drag(b, medium_density(config, b.position));  // no search for a body without drag
    apply_angular_damping(b, config.angular_damping);
}

}  // namespace arena::world
