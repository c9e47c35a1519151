// Contact friction and rotation against closed forms: a box on a slope sticks or slides with
// a = g·(sin θ − μ·cos θ) (in one step and in sub-steps), a ball rolls without slipping
// (ω·r = v), a pyramid of boxes stands, a box of bouncing polygons gains no energy, a scene
// turned a quarter turn turns its results.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "server/world/presets.hpp"
#include "server/world/world.hpp"

using namespace arena::world;

namespace {

// A 3-4-5 slope through the origin: rising 3 m over 4 m, so sin θ = 0.6, cos θ = 0.8.
const vec2 downhill{-0.8f, -0.6f};
const vec2 slope_normal{-0.6f, 0.8f};
const real slope_angle = 0.6435011f;  // atan(3/4), rad

world_config slope_world(uint32_t substeps = 1) {
    world_config c;
    c.substeps = substeps;
    c.gravity = {0, -9.81f};
    c.air_density = 0;
    c.boundary = boundary::open;
    return c;
}

void add_slope(world& w, real friction) {
    body_material ground;
    ground.friction = friction;
    const std::vector<vec2> points{{-40, -30}, {40, 30}};
    REQUIRE(w.add_chain(points, ground));
}

uint32_t add_box_on_slope(world& w, real friction) {
    body_material m;
    m.friction = friction;
    m.restitution = 0;
    const vec2 at = vec2{4, 3} + slope_normal * 0.5f;  // resting on its face
    body b = make_body(m, make_box(0.5f, 0.5f), at);
    b.angle = slope_angle;
    return *w.add_body(b, make_box(0.5f, 0.5f));
}

real along(const vec2& v) {
    return v.dot(downhill);
}

double energy(const world& w) {
    double e = 0;
    for (const body& b : w.bodies())
        e += 0.5 * b.mass * b.velocity.squaredNorm() + 0.5 * b.inertia * b.angular_velocity * b.angular_velocity;
    return e;
}

}  // namespace

TEST_CASE("a box on a slope stays put when tan θ < μ", "[world][friction][substeps]") {
    for (uint32_t substeps : {1u, 4u}) {
        world w(slope_world(substeps), 0);
        add_slope(w, 0.9f);
        const uint32_t id = add_box_on_slope(w, 0.9f);  // tan θ = 0.75 < 0.9
        const vec2 start = w.find(id)->position;
        for (int k = 0; k < 120; ++k) w.step({});
        const body& b = *w.find(id);
        INFO("substeps " << substeps);
        CHECK((b.position - start).norm() < 0.01f);
        CHECK(b.velocity.norm() < 0.01f);
    }
}

TEST_CASE("a box on a slope slides with a = g·(sin θ − μ·cos θ) when tan θ > μ", "[world][friction][substeps]") {
    for (uint32_t substeps : {1u, 4u}) {
        for (real mu : {0.1f, 0.3f, 0.5f}) {
            world w(slope_world(substeps), 0);
            add_slope(w, mu);
            const uint32_t id = add_box_on_slope(w, mu);
            for (int k = 0; k < 30; ++k) w.step({});
            const real v0 = along(w.find(id)->velocity);
            for (int k = 0; k < 60; ++k) w.step({});
            const real v1 = along(w.find(id)->velocity);
            const double expected = 9.81 * (0.6 - mu * 0.8);
            INFO("mu " << mu << ", substeps " << substeps);
            CHECK((v1 - v0) / 1.0 == Approx(expected).epsilon(0.01));
            // It slides, it does not tumble.
            CHECK(std::abs(w.find(id)->angular_velocity) < 0.01f);
        }
    }
}

TEST_CASE("a ball on a slope with friction ends up rolling: ω·r = v", "[world][friction]") {
    world w(slope_world(), 0);
    add_slope(w, 0.6f);
    body_material m;
    m.radius = 0.5f;
    m.friction = 0.6f;
    m.restitution = 0;
    const uint32_t id = *w.add_body(make_body(m, vec2{8, 6} + slope_normal * 0.5f));
    for (int k = 0; k < 120; ++k) w.step({});
    const body& b = *w.find(id);
    const real v = along(b.velocity);
    REQUIRE(v > 1);
    // Rolling downhill to the left turns it counter-clockwise: ω > 0.
    CHECK(b.angular_velocity * 0.5f == Approx(v).epsilon(0.01));
    // A uniform disc rolls with a = (2/3)·g·sin θ; after 2 s, v = a·t.
    CHECK(v == Approx(2.0 / 3 * 9.81 * 0.6 * 2.0).epsilon(0.01));
}

TEST_CASE("a 10-level pyramid of boxes stands for 10 s", "[world][friction]") {
    // The one-step solver (the preset sub-steps: tests/world/substep_tests.cpp).
    world_config c = pyramid_preset(10);
    c.substeps = 1;
    world w(c, 1);
    REQUIRE(w.bodies().size() == 55 + 1);
    const body& top = w.bodies().back();
    const uint32_t top_id = top.id;
    const vec2 start = top.position;
    for (int k = 0; k < 600; ++k) w.step({});
    const body& now = *w.find(top_id);
    CHECK((now.position - start).norm() < 0.01f);
}

TEST_CASE("a closed box of bouncing polygons at restitution 1 gains no energy", "[world][friction]") {
    world_config c;
    c.boundary = boundary::walls;
    c.size = {20, 20};
    c.air_density = 0;
    c.restitution_threshold = 0;
    world w(c, 0);
    rng r(7);
    body_material m;
    m.restitution = 1;
    m.friction = 0.3f;
    for (int i = 0; i < 30; ++i) {
        const shape s = i % 3 == 0 ? make_box(0.6f, 0.3f) : i % 3 == 1 ? make_capsule(0.4f, 0.3f) : make_circle(0.4f);
        const real x = 2 + static_cast<real>(i % 6) * 3;
        const real y = 2 + static_cast<real>(i / 6) * 3.5f;
        body b = make_body(m, s, {x, y});
        const real vx = r.uniform(-5, 5);
        const real vy = r.uniform(-5, 5);
        b.velocity = {vx, vy};
        b.angular_velocity = r.uniform(-2, 2);
        w.add_body(b, s);
    }
    const double before = energy(w);
    double most = before;
    for (int k = 0; k < 600; ++k) {
        w.step({});
        most = std::max(most, energy(w));
    }
    CHECK(most <= before * 1.01);
    CHECK(energy(w) > 0.3 * before);  // they kept moving: it is a test of bounces
}

TEST_CASE("a scene turned a quarter turn gives the turned results", "[world][friction]") {
    // A box dropped, tilted, onto a box resting on a static segment, and the same turned by
    // +90°: (x, y) → (−y, x), gravity and angles turned with it.
    auto run = [](bool turned) {
        world_config c;
        c.air_density = 0;
        c.gravity = turned ? vec2{9.81f, 0} : vec2{0, -9.81f};
        world w(c, 0);
        auto place = [turned](vec2 p) {
            return turned ? vec2{-p.y(), p.x()} : p;
        };
        const real quarter = turned ? 1.5707963f : 0.0f;
        body_material ground;
        const std::vector<vec2> line{place({-10, 0}), place({10, 0})};
        w.add_chain(line, ground);
        body_material m;
        body lower = make_body(m, make_box(0.5f, 0.5f), place({0, 0.5f}));
        lower.angle = quarter;
        w.add_body(lower, make_box(0.5f, 0.5f));
        body upper = make_body(m, make_box(0.4f, 0.4f), place({0.3f, 2.5f}));
        upper.angle = quarter + 0.3f;
        w.add_body(upper, make_box(0.4f, 0.4f));
        for (int k = 0; k < 90; ++k) w.step({});
        std::vector<body> out(w.bodies().begin(), w.bodies().end());
        return out;
    };
    const std::vector<body> a = run(false), b = run(true);
    REQUIRE(a.size() == b.size());
    for (size_t i = 0; i < a.size(); ++i) {
        INFO("body " << i);
        CHECK(b[i].position.x() == Approx(-a[i].position.y()).margin(2e-3));
        CHECK(b[i].position.y() == Approx(a[i].position.x()).margin(2e-3));
        CHECK(b[i].angular_velocity == Approx(a[i].angular_velocity).margin(2e-2));
    }
    // Something happened: the upper box fell and turned.
    CHECK(a[2].position.y() < 2.0f);
    CHECK(std::abs(a[2].angle - 0.3f) > 0.05f);
}
