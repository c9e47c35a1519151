// Forces against closed forms: free fall, terminal velocity, stopping distance, impulses.
#include <catch2/catch.hpp>
#include <cmath>

#include "server/world/world.hpp"

using namespace arena::world;

namespace {

world_config quiet_config(real dt) {
    world_config c;
    c.dt = dt;
    c.air_density = 0;
    return c;
}

uint32_t add_point(world& w, real mass, vec2 position, vec2 velocity = {0, 0}, real drag_area = 0) {
    body_material m;
    m.mass = mass;
    m.radius = 0;
    m.drag_area = drag_area;
    body b = make_body(m, position);
    b.velocity = velocity;
    return *w.add_body(b);
}

}  // namespace

TEST_CASE("free fall follows y = -g t^2 / 2 within the integrator's error", "[world][forces]") {
    const real dt = 1.0f / 600;
    world_config c = quiet_config(dt);
    c.gravity = {0, -9.81f};
    world w(c, 0);
    const uint32_t id = add_point(w, 2, {0, 0});
    for (int k = 0; k < 600; ++k) w.step({});
    const real t = 1.0f;
    // Semi-implicit Euler's error under constant acceleration is g·t·dt/2.
    CHECK(w.find(id)->position.y() == Approx(-0.5f * 9.81f * t * t).margin(0.5 * 9.81 * t * dt * 1.01));
    CHECK(w.find(id)->velocity.y() == Approx(-9.81f * t).epsilon(1e-4));
}

TEST_CASE("drag brings a falling body to the terminal velocity sqrt(2mg/(rho A Cd))", "[world][forces]") {
    world_config c = quiet_config(1.0f / 120);
    c.gravity = {0, -9.81f};
    c.air_density = 1.2f;
    world w(c, 0);
    const real mass = 3, drag_area = 0.4f;  // A·Cd
    const uint32_t id = add_point(w, mass, {0, 0}, {0, 0}, drag_area);
    for (int k = 0; k < 120 * 20; ++k) w.step({});
    const double terminal = std::sqrt(2 * mass * 9.81 / (1.2 * drag_area));
    CHECK(-w.find(id)->velocity.y() == Approx(terminal).epsilon(1e-4));
}

TEST_CASE("a body thrown faster than terminal velocity slows to it without reversing", "[world][forces]") {
    world_config c = quiet_config(1.0f / 60);
    c.air_density = 1000;  // water
    world w(c, 0);
    const uint32_t id = add_point(w, 0.1f, {0, 0}, {50, 0}, 0.5f);
    real previous = 50;
    for (int k = 0; k < 600; ++k) {
        w.step({});
        const real vx = w.find(id)->velocity.x();
        REQUIRE(vx >= 0);  // drag never reverses the motion
        REQUIRE(vx <= previous);
        previous = vx;
    }
}

TEST_CASE("friction stops a sliding body after v0^2/(2 mu g) and it stays at exactly zero", "[world][forces]") {
    const real dt = 1.0f / 600, mu = 0.5f, g = 9.81f, v0 = 10;
    world_config c = quiet_config(dt);
    c.gravity = {0, -g};
    c.boundary = boundary::floor;
    c.floor_friction = mu;
    world w(c, 0);
    const uint32_t id = add_point(w, 5, {0, 0}, {v0, 0});
    int steps = 0;
    while (w.find(id)->velocity.x() != 0 && steps < 100000) {
        w.step({});
        ++steps;
        REQUIRE(w.find(id)->velocity.x() >= 0);
    }
    const double expected = v0 * v0 / (2 * mu * g);
    CHECK(w.find(id)->position.x() == Approx(expected).epsilon(0.005));
    CHECK(w.find(id)->position.y() == 0.0f);  // the normal force holds it on the floor
    const real stopped_at = w.find(id)->position.x();
    for (int k = 0; k < 600; ++k) w.step({});
    CHECK(w.find(id)->velocity.x() == 0.0f);
    CHECK(w.find(id)->velocity.y() == 0.0f);
    CHECK(w.find(id)->position.x() == stopped_at);
}

TEST_CASE("an impulse changes velocity by exactly J/m", "[world][forces]") {
    world w(quiet_config(1.0f / 60), 0);
    const uint32_t id = add_point(w, 4, {0, 0}, {1, 2});
    w.find(id)->apply_impulse({8, -2});
    CHECK(w.find(id)->velocity.x() == 3.0f);
    CHECK(w.find(id)->velocity.y() == 1.5f);
    body& b = *w.find(id);
    const real omega = b.angular_velocity;
    b.inv_inertia = 0.25f;
    b.apply_angular_impulse(2);
    CHECK(b.angular_velocity == omega + 0.5f);
}

TEST_CASE("accumulators are cleared at the end of every step", "[world][forces]") {
    world w(quiet_config(1.0f), 0);
    const uint32_t id = add_point(w, 1, {0, 0});
    w.find(id)->apply_force({10, 0});
    w.find(id)->apply_torque(3);
    w.step({});
    CHECK(w.find(id)->force == vec2{0, 0});
    CHECK(w.find(id)->torque == 0.0f);
    w.step({});
    CHECK(w.find(id)->velocity.x() == 10.0f);  // no force in the second step
}

TEST_CASE("a player's thrust pushes along its facing and button 0 fires an impulse with a cooldown",
          "[world][forces]") {
    world_config c = quiet_config(1.0f / 60);
    c.control.thrust_force = 60;
    c.control.impulse = 10;
    c.control.impulse_cooldown_ticks = 5;
    c.player.mass = 2;
    world w(c, 7);
    const body_id id = *w.spawn_player(player_id{1});
    w.step({{id, {1, 0, 0}}});
    CHECK(w.find(id)->velocity.x() == Approx(60.0 / 2 / 60));
    CHECK(w.find(id)->velocity.y() == 0.0f);
    const real before = w.find(id)->velocity.x();
    w.step({{id, {0, 0, button_impulse}}});
    CHECK(w.find(id)->velocity.x() == Approx(before + 5));
    for (int k = 0; k < 3; ++k) w.step({{id, {0, 0, button_impulse}}});  // cooling down
    CHECK(w.find(id)->velocity.x() == Approx(before + 5));
}

TEST_CASE("water drags harder than air", "[world][forces]") {
    world_config c = quiet_config(1.0f / 60);
    c.fluids = {fluid_region{{10, -5}, {20, 5}, 1000}};
    c.air_density = 1.2f;
    world w(c, 0);
    const uint32_t in_air = add_point(w, 1, {0, 0}, {5, 0}, 0.5f);
    const uint32_t in_water = add_point(w, 1, {15, 0}, {5, 0}, 0.5f);
    w.step({});
    CHECK(w.find(in_water)->velocity.x() < w.find(in_air)->velocity.x() * 0.5f);
}
