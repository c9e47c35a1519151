// Chains (world::add_chain) against closed forms: a box slides along a chain of many short
// segments with a = −μ·g as on one long segment and does not hop at the joints (ghost vertices),
// a ball rolls across the joints at a constant speed, convex and concave corners still hold
// bodies, and a chain is solid on one side only.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "server/world/world.hpp"

using namespace arena::world;

namespace {

constexpr real g = 9.81f;
constexpr real dt = 1.0f / 60.0f;

world_config ground_world() {
    world_config c;
    c.gravity = {0, -g};
    c.air_density = 0;
    c.boundary = boundary::open;
    return c;
}

// Flat ground at y = 0 from x = −10 to x = 90, in `pieces` equal segments (left to right: the
// solid face is up).
std::vector<vec2> flat_points(int pieces) {
    std::vector<vec2> points;
    for (int k = 0; k <= pieces; ++k)
        points.push_back({-10 + 100 * static_cast<real>(k) / static_cast<real>(pieces), 0});
    return points;
}

body_material with_friction(real mu) {
    body_material m;
    m.friction = mu;
    m.restitution = 0;
    return m;
}

// A body's path, tick by tick.
struct track {
    std::vector<real> vx, y, vy, spin;
};

track run(world& w, uint32_t id, int ticks) {
    track t;
    for (int k = 0; k < ticks; ++k) {
        w.step({});
        const body& b = *w.find(id);
        t.vx.push_back(b.velocity.x());
        t.y.push_back(b.position.y());
        t.vy.push_back(b.velocity.y());
        t.spin.push_back(b.angular_velocity);
    }
    return t;
}

// A 1 m box of friction μ launched at 6 m/s to the right along flat ground of `pieces` segments.
track slide_box(int pieces, real mu, int ticks) {
    world w(ground_world(), 0);
    REQUIRE(w.add_chain(flat_points(pieces), with_friction(mu)));
    body b = make_body(with_friction(mu), make_box(0.5f, 0.5f), {0, 0.5f});
    b.velocity = {6, 0};
    return run(w, *w.add_body(b, make_box(0.5f, 0.5f)), ticks);
}

real largest_gap(const std::vector<real>& a, const std::vector<real>& b, size_t from) {
    real most = 0;
    for (size_t k = from; k < a.size(); ++k) most = std::max(most, std::abs(a[k] - b[k]));
    return most;
}

real largest(const std::vector<real>& a, size_t from) {
    real most = 0;
    for (size_t k = from; k < a.size(); ++k) most = std::max(most, std::abs(a[k]));
    return most;
}

}  // namespace

TEST_CASE("a box slides along a chain of short segments with a = −μ·g, as on one segment", "[world][chain]") {
    // 400 segments of 25 cm: the box (1 m wide) always straddles three or four joints and
    // crosses about 14 of them while it slows from 6 m/s.
    for (real mu : {0.2f, 0.5f}) {
        INFO("mu " << mu);
        const int ticks = 60;  // stops after 6/(μ·g) ≥ 1.2 s
        const track chain = slide_box(400, mu, ticks);
        const track one = slide_box(1, mu, ticks);
        // From tick 10 (settled) to tick 55: 45 steps.
        const double measured = (chain.vx[55] - chain.vx[10]) / (45 * dt);
        CHECK(measured == Approx(-mu * g).epsilon(0.01));
        CHECK((one.vx[55] - one.vx[10]) / (45 * dt) == Approx(-mu * g).epsilon(0.01));
        CHECK(largest_gap(chain.vx, one.vx, 0) < 0.01f * 6);
        // It neither hops nor tips at the joints.
        CHECK(largest_gap(chain.y, one.y, 0) < 0.001f);
        CHECK(largest(chain.vy, 5) < 0.02f);
        CHECK(largest(chain.spin, 5) < 0.02f);
    }
}

TEST_CASE("a ball rolls across the joints of a chain at a constant speed", "[world][chain]") {
    auto roll = [](int pieces) {
        world w(ground_world(), 0);
        REQUIRE(w.add_chain(flat_points(pieces), with_friction(0.6f)));
        body_material m = with_friction(0.6f);
        m.radius = 0.5f;
        body b = make_body(m, {0, 0.5f});
        b.velocity = {4, 0};
        b.angular_velocity = -4 / 0.5f;  // rolling: v = −ω·r
        return run(w, *w.add_body(b), 90);
    };
    const track chain = roll(400);  // 1.5 s at 4 m/s: 24 joints
    const track one = roll(1);
    for (size_t k = 0; k < chain.vx.size(); ++k) {
        INFO("tick " << k);
        REQUIRE(chain.vx[k] == Approx(4).epsilon(0.01));
    }
    CHECK(largest_gap(chain.vx, one.vx, 0) < 0.01f * 4);
    CHECK(largest_gap(chain.y, one.y, 0) < 0.001f);
    CHECK(largest(chain.vy, 5) < 0.02f);
}

TEST_CASE("a box dropped on a convex corner lands on it and slides down one side", "[world][chain]") {
    // A roof: up from (−20, −20) to the ridge at (0, 0), down to (20, −20).
    world w(ground_world(), 0);
    const std::vector<vec2> roof{{-20, -20}, {0, 0}, {20, -20}};
    REQUIRE(w.add_chain(roof, with_friction(0.2f)));
    const uint32_t id =
        *w.add_body(make_body(with_friction(0.2f), make_box(0.5f, 0.5f), {0.3f, 1.5f}), make_box(0.5f, 0.5f));
    real deepest = 0;  // the deepest any corner of the box went below the roof (m)
    for (int k = 0; k < 90; ++k) {
        w.step({});
        const body& b = *w.find(id);
        const real c = std::cos(b.angle), s = std::sin(b.angle);
        for (const vec2& corner : {vec2{-0.5f, -0.5f}, vec2{0.5f, -0.5f}, vec2{0.5f, 0.5f}, vec2{-0.5f, 0.5f}}) {
            const vec2 p = b.position + vec2{c * corner.x() - s * corner.y(), s * corner.x() + c * corner.y()};
            // Distance below the roof's surface, measured along its normal.
            const real below = (-std::abs(p.x()) - p.y()) * 0.70710678f;
            deepest = std::max(deepest, below);
        }
    }
    const body& b = *w.find(id);
    CHECK(deepest < 0.01f);
    // On the right slope, sliding down it: a = g·(sin 45° − μ·cos 45°) > 0.
    CHECK(b.position.x() > 1);
    CHECK(b.velocity.x() > 1);
    CHECK(b.velocity.y() == Approx(-b.velocity.x()).epsilon(0.05));
}

TEST_CASE("a ball settles in a concave corner touching both sides", "[world][chain]") {
    // A valley: down from (−5, 5) to (0, 0), up to (5, 5). A ball resting in it touches both
    // slopes: its centre lies r·√2 above the bottom.
    world w(ground_world(), 0);
    const std::vector<vec2> valley{{-5, 5}, {0, 0}, {5, 5}};
    REQUIRE(w.add_chain(valley, with_friction(0.6f)));
    body_material m = with_friction(0.6f);
    m.radius = 0.5f;
    const uint32_t id = *w.add_body(make_body(m, {0.4f, 3}));
    for (int k = 0; k < 300; ++k) w.step({});
    const body& b = *w.find(id);
    CHECK(std::abs(b.position.x()) < 0.01f);
    CHECK(b.position.y() == Approx(0.5f * std::sqrt(2.0f)).margin(0.006));
    CHECK(b.velocity.norm() < 0.01f);
}

TEST_CASE("a box pushed into the concave corner of a floor and a wall stops at the wall", "[world][chain]") {
    // A floor from (−10, 0) to (0, 0), then a wall up to (0, 10): solid on the left of the chain,
    // that is above the floor and left of the wall.
    world w(ground_world(), 0);
    const std::vector<vec2> corner{{-10, 0}, {0, 0}, {0, 10}};
    REQUIRE(w.add_chain(corner, with_friction(0)));
    body box = make_body(with_friction(0), make_box(0.5f, 0.5f), {-3, 0.5f});
    box.velocity = {4, 0};
    const uint32_t id = *w.add_body(box, make_box(0.5f, 0.5f));
    real lowest = 1, highest = 0;
    for (int k = 0; k < 120; ++k) {
        w.step({});
        lowest = std::min(lowest, w.find(id)->position.y());
        highest = std::max(highest, w.find(id)->position.y());
    }
    const body& b = *w.find(id);
    CHECK(b.position.x() == Approx(-0.5f).margin(0.006));
    CHECK(lowest > 0.49f);
    CHECK(highest < 0.505f);
    CHECK(std::abs(b.velocity.x()) < 0.01f);
    CHECK(std::abs(b.angular_velocity) < 0.01f);
}

TEST_CASE("a chain is solid on its left only: a one-way floor", "[world][chain]") {
    // The floor runs left to right: a ball falling on it from above stays on it, a ball thrown
    // up from below passes through.
    world w(ground_world(), 0);
    REQUIRE(w.add_chain(flat_points(10), with_friction(0.6f)));
    body_material m = with_friction(0.6f);
    m.radius = 0.25f;
    const uint32_t above = *w.add_body(make_body(m, {5, 2}));
    body thrown = make_body(m, {20, -1});
    thrown.velocity = {0, 8};  // rises 3.2 m: its top passes y = 0 at 5 m/s
    const uint32_t below = *w.add_body(thrown);
    for (int k = 0; k < 60; ++k) w.step({});
    CHECK(w.find(above)->position.y() == Approx(0.25f).margin(0.006));
    CHECK(w.find(below)->position.y() > 1);
}

TEST_CASE("a chain's segments know their neighbours and a closed loop links its ends", "[world][chain]") {
    world w(ground_world(), 0);
    // Clockwise: solid inside, so a box dropped on top of it rests there.
    const std::vector<vec2> loop{{0, 0}, {0, 2}, {4, 2}, {4, 0}, {0, 0}};
    const auto ids = w.add_chain(loop, with_friction(0.6f));
    REQUIRE(ids);
    REQUIRE(ids->size() == 4);
    for (uint32_t id : *ids) {
        const shape s = w.shape_of(*w.find(id));
        CHECK(s.chain.linked);
        CHECK(s.chain.has_prev);
        CHECK(s.chain.has_next);
    }
    const std::vector<vec2> open{{10, 0}, {12, 0}, {14, 0}};
    const auto line = w.add_chain(open, with_friction(0.6f));
    REQUIRE(line);
    const shape first = w.shape_of(*w.find(line->front()));
    const shape last = w.shape_of(*w.find(line->back()));
    CHECK(!first.chain.has_prev);
    CHECK(first.chain.has_next);
    CHECK(last.chain.has_prev);
    CHECK(!last.chain.has_next);
    const uint32_t box =
        *w.add_body(make_body(with_friction(0.6f), make_box(0.5f, 0.5f), {2, 3}), make_box(0.5f, 0.5f));
    for (int k = 0; k < 120; ++k) w.step({});
    CHECK(w.find(box)->position.y() == Approx(2.5f).margin(0.006));
    // Two equal points in a row make no segment: refused, nothing added.
    const size_t before = w.bodies().size();
    const std::vector<vec2> repeated{{0, 10}, {1, 10}, {1, 10}, {2, 10}};
    CHECK(!w.add_chain(repeated, with_friction(0.6f)));
    CHECK(w.bodies().size() == before);
}
