#include "server/world/hash.hpp"

namespace arena::world {

namespace {

void add_material(fnv1a& h, const body_material& m) {
    h.add_real(m.density);
    h.add_real(m.mass);
    h.add_real(m.radius);
    h.add_real(m.restitution);
    h.add_real(m.friction);
    h.add_real(m.drag_area);
    h.add_u8(m.fixed_rotation);
}

}  // namespace

uint64_t config_hash(const world_config& c) {
    fnv1a h;
    h.add_real(c.dt);
    h.add_u8(static_cast<uint8_t>(c.integrator));
    h.add_vec2(c.gravity);
    h.add_real(c.air_density);
    h.add_u32(static_cast<uint32_t>(c.fluids.size()));
    for (const fluid_region& f : c.fluids) {
        h.add_vec2(f.min);
        h.add_vec2(f.max);
        h.add_real(f.density);
    }
    h.add_u8(static_cast<uint8_t>(c.boundary));
    h.add_vec2(c.size);
    h.add_real(c.floor_friction);
    h.add_real(c.angular_damping);
    h.add_u32(c.velocity_iterations);
    h.add_u32(c.position_iterations);
    h.add_real(c.restitution_threshold);
    h.add_real(c.penetration_slop);
    h.add_real(c.speculative_distance);
    h.add_real(c.correction_fraction);
    h.add_real(c.max_correction);
    h.add_u32(c.max_bodies);
    add_material(h, c.player);
    h.add_real(c.control.thrust_force);
    h.add_real(c.control.turn_torque);
    h.add_real(c.control.impulse);
    h.add_u32(c.control.impulse_cooldown_ticks);
    h.add_u8(c.control.thrust_along_facing);
    h.add_u8(c.control.impulse_upward);
    h.add_u8(c.control.impulse_needs_ground);
    h.add_u32(c.rocks.count);
    h.add_real(c.rocks.min_radius);
    h.add_real(c.rocks.max_radius);
    h.add_real(c.rocks.max_speed);
    add_material(h, c.rocks.material);
    h.add_u32(c.rocks.polygon_vertices);
    h.add_u32(static_cast<uint32_t>(c.bodies.size()));
    for (const body_config& b : c.bodies) {
        h.add_u8(static_cast<uint8_t>(b.shape.type));
        h.add_real(b.shape.radius);
        h.add_real(b.shape.rounding);
        h.add_vec2(b.shape.half_extents);
        h.add_real(b.shape.half_length);
        h.add_u32(static_cast<uint32_t>(b.shape.points.size()));
        for (const vec2& p : b.shape.points) h.add_vec2(p);
        add_material(h, b.material);
        h.add_vec2(b.position);
        h.add_real(b.angle);
        h.add_vec2(b.velocity);
        h.add_u8(b.is_static);
    }
    // Only rules other than the sandbox's: configs from before rules existed keep their hashes.
    if (c.rules != "sandbox") {
        h.add_u8(0x52);
        h.add_u32(static_cast<uint32_t>(c.rules.size()));
        h.add_bytes(c.rules);
    }
    // Only configs with the game's parameters: configs from before them keep their hashes.
    if (!c.rules_params.empty()) {
        h.add_u8(0x54);
        h.add_u32(static_cast<uint32_t>(c.rules_params.size()));
        h.add_bytes(c.rules_params);
    }
    // Only sub-stepped configs: configs from before sub-steps existed keep their hashes.
    if (c.substeps != 1) {
        h.add_u8(0x53);
        h.add_u32(c.substeps);
    }
    return h.value();
}

}  // namespace arena::world
