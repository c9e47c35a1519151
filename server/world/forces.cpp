#include "server/world/forces.hpp"

#include <cmath>

#include "server/world/trig.hpp"

namespace arena::world {

void apply_player_input(body& b, const player_input& input, const control_config& control, bool on_ground) {
    const cos_sin facing = compute_cos_sin(b.angle);
    const vec2 thrust_dir = control.thrust_along_facing ? vec2{facing.c, facing.s} : vec2{1, 0};
    b.apply_force(thrust_dir * (input.thrust * control.thrust_force));
    b.apply_torque(input.turn * control.turn_torque);
    const bool wants_impulse = (input.buttons & button_impulse) != 0;
    const bool allowed = b.impulse_cooldown == 0 && (!control.impulse_needs_ground || on_ground);
    if (wants_impulse && allowed) {
        const vec2 impulse_dir = control.impulse_upward ? vec2{0, 1} : vec2{facing.c, facing.s};
        b.apply_impulse(impulse_dir * control.impulse);
        b.impulse_cooldown = control.impulse_cooldown_ticks;
    }
}

void apply_weight(body& b, const vec2& gravity) {
    if (!b.is_static()) b.apply_force(gravity * b.mass);
}

void apply_floor_contact(body& b, const vec2& gravity, real friction) {
    // A body moving away from the floor (a jump) feels neither its push nor its friction.
    if (b.is_static() || gravity.y() >= 0 || b.velocity.y() > 0) return;
    const real normal = b.mass * -gravity.y();  // N
    b.apply_force(vec2{0, normal});
    if (b.velocity.x() != 0) b.resistance.x() -= friction * normal * (b.velocity.x() > 0 ? 1.0f : -1.0f);
}

void apply_drag(body& b, real rho) {
    if (b.drag_area == 0 || rho == 0) return;
    const real speed_sq = b.velocity.squaredNorm();
    if (speed_sq == 0) return;
    // −½ρ|v|²·ACd·v̂ = −½ρ|v|·ACd·v: one sqrt instead of a normalisation.
    const real speed = std::sqrt(speed_sq);
    b.resistance -= b.velocity * (0.5f * rho * b.drag_area * speed);
}

void apply_angular_damping(body& b, real damping) {
    if (damping == 0 || b.inv_inertia == 0) return;
    b.resistance_torque -= damping * b.inertia * b.angular_velocity;
}

real medium_density(const world_config& config, const vec2& position) {
    for (const fluid_region& f : config.fluids) {
        if (position.x() >= f.min.x() && position.x() <= f.max.x() && position.y() >= f.min.y() &&
            position.y() <= f.max.y())
            return f.density;
    }
    return config.air_density;
}

}  // namespace arena::world
