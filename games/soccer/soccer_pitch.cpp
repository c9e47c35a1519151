#include "games/soccer/soccer_pitch.hpp"

namespace arena::rules {

world::world_config soccer_pitch() {
    using world::vec2;
    const pitch_geometry& p = pitch;
    world::world_config c;
    c.boundary = world::boundary::open;  // the chain below holds everything in
    c.size = {p.right + p.left, p.top + p.bottom};
    c.gravity = {0, 0};
    c.air_density = 1.2f;
    c.angular_damping = 4.0f;
    // A 70 kg player, 1 m across: 500 N of running force against drag A·Cd = 4 m² gives a top
    // speed of √(2·500 / (1.2·4)) ≈ 14 m/s; turning, it stops spinning in about a second.
    c.player = {.density = 1, .mass = 70, .radius = 1.0f, .restitution = 0.2f, .friction = 0.3f, .drag_area = 4.0f};
    c.control = {.thrust_force = 500,
                 .turn_torque = 300,
                 .impulse = 140,  // a dash: Δv = 2 m/s, once a second
                 .impulse_cooldown_ticks = 60,
                 .thrust_along_facing = true,
                 .impulse_upward = false,
                 .impulse_needs_ground = false};
    // Walls and goals, counter-clockwise so that the inside is solid (a chain is solid on its
    // left): along the bottom line, into the right goal and out, along the top line, into the
    // left goal and out. The corners are cut at 45°: a ball in a corner rolls out of it.
    const world::real goal_low = p.centre().y() - p.goal_half_width;
    const world::real goal_high = p.centre().y() + p.goal_half_width;
    const world::real cut = p.corner_cut;
    world::body_config walls;
    walls.shape.type = world::shape_type::chain;
    walls.shape.points = {
        {p.left + cut, p.bottom},
        {p.right - cut, p.bottom},
        {p.right, p.bottom + cut},
        {p.right, goal_low},
        {p.right + p.goal_depth, goal_low},
        {p.right + p.goal_depth, goal_high},
        {p.right, goal_high},
        {p.right, p.top - cut},
        {p.right - cut, p.top},
        {p.left + cut, p.top},
        {p.left, p.top - cut},
        {p.left, goal_high},
        {p.left - p.goal_depth, goal_high},
        {p.left - p.goal_depth, goal_low},
        {p.left, goal_low},
        {p.left, p.bottom + cut},
        {p.left + cut, p.bottom},
    };
    walls.material = {.density = 0, .mass = 0, .radius = 1, .restitution = 0.5f, .friction = 0.2f};
    walls.is_static = true;
    c.bodies.push_back(walls);
    // The ball: 0.45 kg, 1 m across, a lively bounce, little drag (A·Cd = 0.01 m²).
    world::body_config ball;
    ball.shape.type = world::shape_type::circle;
    ball.shape.radius = p.ball_radius;
    ball.material = {
        .density = 0, .mass = 0.45f, .radius = 1, .restitution = 0.6f, .friction = 0.2f, .drag_area = 0.01f};
    ball.position = p.centre();
    c.bodies.push_back(ball);
    c.rules = "soccer";
    return c;
}

}  // namespace arena::rules
