// Circle collisions: momentum, energy with restitution 1, resting stacks, walls and wrap.
#include <catch2/catch.hpp>
#include <cmath>

#include "server/world/world.hpp"

using namespace arena::world;

namespace {

world_config space(real restitution_threshold = 1.0f) {
    world_config c;
    c.air_density = 0;
    c.restitution_threshold = restitution_threshold;
    return c;
}

// Frictionless, so that an off-centre impact spins nothing and the translational energy and
// momentum are the whole story (friction has its own tests: friction_tests.cpp).
uint32_t add_ball(world& w, real radius, real mass, vec2 p, vec2 v, real restitution) {
    body_material m;
    m.mass = mass;
    m.radius = radius;
    m.restitution = restitution;
    m.friction = 0;
    body b = make_body(m, p);
    b.velocity = v;
    return *w.add_body(b);
}

vec2 momentum(const world& w) {
    vec2 p{0, 0};
    for (const body& b : w.bodies()) p += b.velocity * b.mass;
    return p;
}

double kinetic_energy(const world& w) {
    double e = 0;
    for (const body& b : w.bodies()) e += 0.5 * b.mass * b.velocity.squaredNorm();
    return e;
}

}  // namespace

TEST_CASE("collisions conserve momentum", "[world][collision]") {
    world w(space(), 0);
    add_ball(w, 1, 2, {0, 0}, {3, 0.5f}, 0.3f);
    add_ball(w, 1.5f, 5, {4, 0.8f}, {-2, 0}, 0.6f);
    const vec2 before = momentum(w);
    bool touched = false;
    for (int k = 0; k < 120; ++k) {
        w.step({});
        touched = touched || !w.last_contacts().empty();
    }
    REQUIRE(touched);
    const vec2 after = momentum(w);
    CHECK(after.x() == Approx(before.x()).margin(1e-4));
    CHECK(after.y() == Approx(before.y()).margin(1e-4));
}

TEST_CASE("with restitution 1 collisions conserve kinetic energy", "[world][collision]") {
    world w(space(0.0f), 0);
    add_ball(w, 1, 1, {0, 0}, {4, 0}, 1);
    add_ball(w, 1, 3, {5, 0.7f}, {-1, 0}, 1);
    const double before = kinetic_energy(w);
    const vec2 p_before = momentum(w);
    for (int k = 0; k < 120; ++k) w.step({});
    CHECK(kinetic_energy(w) == Approx(before).epsilon(1e-4));
    CHECK(momentum(w).x() == Approx(p_before.x()).margin(1e-4));
    // They did collide: the light ball came back.
    CHECK(w.bodies()[0].velocity.x() < 0);
}

TEST_CASE("a head-on elastic collision of equal masses swaps velocities", "[world][collision]") {
    world w(space(0.0f), 0);
    const uint32_t a = add_ball(w, 1, 1, {0, 0}, {2, 0}, 1);
    const uint32_t b = add_ball(w, 1, 1, {3, 0}, {-2, 0}, 1);
    for (int k = 0; k < 60; ++k) w.step({});
    CHECK(w.find(a)->velocity.x() == Approx(-2).margin(1e-5));
    CHECK(w.find(b)->velocity.x() == Approx(2).margin(1e-5));
}

TEST_CASE("a resting stack stays put for 10 s of ticks", "[world][collision]") {
    world_config c;
    c.boundary = boundary::walls;
    c.size = {20, 20};
    c.gravity = {0, -9.81f};
    c.floor_friction = 0.5f;
    world w(c, 0);
    std::vector<uint32_t> ids;
    for (int i = 0; i < 4; ++i) ids.push_back(add_ball(w, 0.5f, 1, {10, 0.5f + static_cast<real>(i)}, {0, 0}, 0.2f));
    std::vector<vec2> start;
    for (uint32_t id : ids) start.push_back(w.find(id)->position);
    for (int k = 0; k < 600; ++k) w.step({});
    for (size_t i = 0; i < ids.size(); ++i) {
        const body& b = *w.find(ids[i]);
        INFO("body " << i);
        CHECK((b.position - start[i]).norm() < 0.02f);  // no sinking beyond the slop
        CHECK(b.velocity.norm() < 0.05f);               // no jitter
        CHECK(b.position.y() >= 0.5f + static_cast<real>(i) - 0.02f);
    }
}

TEST_CASE("walls keep bodies inside and bounce them back", "[world][collision]") {
    world_config c = space();
    c.boundary = boundary::walls;
    c.size = {10, 10};
    world w(c, 0);
    const uint32_t id = add_ball(w, 0.5f, 1, {5, 5}, {20, 13}, 1);
    for (int k = 0; k < 600; ++k) {
        w.step({});
        const body& b = *w.find(id);
        REQUIRE(b.position.x() >= 0.5f - 0.4f);
        REQUIRE(b.position.x() <= 9.5f + 0.4f);
        REQUIRE(b.position.y() >= 0.5f - 0.4f);
        REQUIRE(b.position.y() <= 9.5f + 0.4f);
    }
    CHECK(w.find(id)->velocity.norm() == Approx(std::sqrt(20.0 * 20 + 13 * 13)).epsilon(1e-3));
}

TEST_CASE("wrap-around sends a body out of one side and in at the other", "[world][collision]") {
    world_config c = space();
    c.boundary = boundary::wrap;
    c.size = {10, 10};
    world w(c, 0);
    const uint32_t id = add_ball(w, 0.5f, 1, {9.9f, 5}, {6, -6}, 1);
    w.step({});
    const body& b = *w.find(id);
    CHECK(b.position.x() >= 0);
    CHECK(b.position.x() < 1);
    CHECK(b.position.y() < 5);
}

TEST_CASE("bodies touching across the wrap seam collide", "[world][collision]") {
    world_config c = space();
    c.boundary = boundary::wrap;
    c.size = {100, 100};
    world w(c, 0);
    const uint32_t a = add_ball(w, 1, 1, {99.5f, 50}, {0, 0}, 1);
    add_ball(w, 1, 1, {0.8f, 50}, {0, 0}, 1);
    w.step({});
    REQUIRE(w.last_contacts().size() == 1);
    CHECK(w.find(a)->position.x() < 99.5f);  // pushed apart across the seam
}
