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
    c.rocks.polygon_vertices = 7;  // irregular heptagons, like the arcade game's rocks
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
    // Level geometry: a ramp from the floor up to the first platform, two more platforms.
    auto platform = [](vec2 centre, real half_width) {
        body_config b;
        b.shape.type = shape_type::box;
        b.shape.half_extents = {half_width, 0.25f};
        b.position = centre;
        b.is_static = true;
        return b;
    };
    c.bodies.push_back(platform({22, 4}, 4));  // top at y = 4.25, x in [18, 26]
    c.bodies.push_back(platform({36, 7}, 3));
    c.bodies.push_back(platform({48, 10}, 4));
    body_config ramp;
    ramp.shape.type = shape_type::segment;
    ramp.shape.points = {{10, 0}, {18, 4.25f}};  // about 28°
    c.bodies.push_back(ramp);
    // Crates: 1 m boxes of 20 kg (a runner's 1000 N pushes one against μ·m·g ≈ 120 N), one
    // alone and a stack of four.
    auto crate = [](vec2 centre) {
        body_config b;
        b.shape.type = shape_type::box;
        b.shape.half_extents = {0.5f, 0.5f};
        b.material = {.density = 20, .mass = 0, .radius = 1, .restitution = 0.1f, .friction = 0.6f, .drag_area = 0.3f};
        b.position = centre;
        return b;
    };
    c.bodies.push_back(crate({30, 0.5f}));
    for (int level = 0; level < 4; ++level) c.bodies.push_back(crate({42, 0.5f + static_cast<real>(level)}));
    return c;
}

world_config pyramid_preset(uint32_t base) {
    world_config c;
    c.boundary = boundary::open;
    c.gravity = {0, -10};
    c.air_density = 0;
    c.size = {2.0f * static_cast<real>(base) + 20, static_cast<real>(base) + 10};
    c.max_bodies = base * (base + 1) / 2 + 16;
    c.rocks.count = 0;
    // Box2D v3's benchmark steps: 1/60 s in 4 sub-steps (soft_solver.hpp), which keeps a tall
    // stack stiff at a fraction of the cost of 4 whole steps.
    c.substeps = 4;
    c.player = {.density = 1, .mass = 0, .radius = 0.5f, .restitution = 0, .drag_area = 0};
    body_config ground;
    ground.shape.type = shape_type::segment;
    const real half = static_cast<real>(base) + 10;
    ground.shape.points = {{-half, 0}, {half, 0}};
    ground.position = {c.size.x() * 0.5f, 0};
    c.bodies.push_back(ground);
    // Row i (from 0 at the bottom) holds base − i boxes, centred, 1 m apart, resting on row i − 1.
    for (uint32_t i = 0; i < base; ++i) {
        for (uint32_t j = i; j < base; ++j) {
            body_config box;
            box.shape.type = shape_type::box;
            box.shape.half_extents = {0.5f, 0.5f};
            box.material = {.density = 1, .mass = 0, .radius = 1, .restitution = 0, .friction = 0.6f, .drag_area = 0};
            const real x =
                static_cast<real>(i) * 0.5f + static_cast<real>(j - i) - 0.5f * static_cast<real>(base) + 0.5f;
            box.position = {c.size.x() * 0.5f + x, 0.5f + static_cast<real>(i)};
            c.bodies.push_back(box);
        }
    }
    return c;
}

std::optional<world_config> preset_by_name(std::string_view name) {
    if (name == "asteroids") return asteroids_preset();
    if (name == "platformer") return platformer_preset();
    if (name == "pyramid") return pyramid_preset();
    return std::nullopt;
}

std::vector<std::string_view> preset_names() {
    return {"asteroids", "platformer", "pyramid"};
}

}  // namespace arena::world
