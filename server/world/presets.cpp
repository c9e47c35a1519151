#include "server/world/presets.hpp"

namespace arena::world {

world_config asteroids_preset() {
    world_config c;
    c.boundary = boundary::wrap;
    c.size = {400, 400};
    c.gravity = {0, 0};
    c.air_density = 1.2f;
    c.angular_damping = 2.0f;
    // A 10 kg ship, 1.5 m across: 200 N of thrust against drag ACd 0.5 gives a top speed of
    // √(2·200 / (1.2·0.5)) ≈ 26 m/s.
    c.player = {.density = 1, .mass = 10, .radius = 1.5f, .restitution = 0.5f, .drag_area = 0.5f};
    c.control = {.thrust_force = 200,
                 .turn_torque = 60,
                 .impulse = 50,
                 .impulse_cooldown_ticks = 30,
                 .thrust_along_facing = true,
                 .impulse_upward = false,
                 .impulse_needs_ground = false};
    c.rocks.count = 40;
    c.rocks.min_radius = 2;
    c.rocks.max_radius = 6;
    c.rocks.max_speed = 6;
    c.rocks.material = {.density = 1, .mass = 0, .radius = 1, .restitution = 0.8f, .drag_area = 0.02f};
    return c;
}

world_config platformer_preset() {
    world_config c;
    c.boundary = boundary::walls;
    c.size = {100, 50};
    c.gravity = {0, -9.81f};
    c.air_density = 1.2f;
    c.floor_friction = 0.6f;
    // Water fills the right part of the floor, 12 m deep.
    c.fluids = {fluid_region{.min = {60, 0}, .max = {85, 12}, .density = 1000}};
    // A 70 kg runner that never rotates: 1000 N of running force against μN = 412 N of
    // friction, a 350 N·s jump (Δv = 5 m/s).
    c.player = {
        .density = 1, .mass = 70, .radius = 0.5f, .restitution = 0.1f, .drag_area = 0.5f, .fixed_rotation = true};
    c.control = {.thrust_force = 1000,
                 .turn_torque = 0,
                 .impulse = 350,
                 .impulse_cooldown_ticks = 20,
                 .thrust_along_facing = false,
                 .impulse_upward = true,
                 .impulse_needs_ground = true};
    c.rocks.count = 8;
    c.rocks.min_radius = 0.5f;
    c.rocks.max_radius = 1.0f;
    c.rocks.max_speed = 3;
    c.rocks.material = {.density = 20, .mass = 0, .radius = 1, .restitution = 0.3f, .drag_area = 0.3f};
    return c;
}

std::optional<world_config> preset_by_name(std::string_view name) {
    if (name == "asteroids") return asteroids_preset();
    if (name == "platformer") return platformer_preset();
    return std::nullopt;
}

std::vector<std::string_view> preset_names() {
    return {"asteroids", "platformer"};
}

}  // namespace arena::world
