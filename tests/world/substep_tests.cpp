// The sub-stepped solver (world_config::substeps > 1, soft_solver.hpp): tall stacks stand, a
// bounce keeps its coefficient of restitution, the same config gives the same bits, and one
// sub-step is still the one-step solver's bits. Slopes in sub-steps: friction_tests.cpp.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "server/world/presets.hpp"
#include "server/world/world.hpp"

using namespace arena::world;

namespace {

// The top box's distance from where it started after `steps` steps of a pyramid of `base`.
real top_drift(uint32_t base, uint32_t substeps, int steps) {
    world_config c = pyramid_preset(base);
    c.substeps = substeps;
    world w(c, 1);
    REQUIRE(w.bodies().size() == base * (base + 1) / 2 + 1);
    const uint32_t top_id = w.bodies().back().id;
    const vec2 start = w.find(top_id)->position;
    for (int k = 0; k < steps; ++k) w.step({});
    return (w.find(top_id)->position - start).norm();
}

}  // namespace

TEST_CASE("a 10-level pyramid stands for 10 s in 4 sub-steps", "[world][substeps]") {
    CHECK(top_drift(10, 4, 600) < 0.01f);
}

TEST_CASE("a 20-level pyramid stands for 10 s in 4 sub-steps", "[world][substeps]") {
    CHECK(top_drift(20, 4, 600) < 0.01f);
}

TEST_CASE("the pyramid preset steps in 4 sub-steps", "[world][substeps]") {
    CHECK(pyramid_preset(10).substeps == 4);
}

TEST_CASE("a ball dropped in sub-steps bounces back at e times its impact speed", "[world][substeps]") {
    for (real e : {0.3f, 0.5f, 0.8f}) {
        world_config c;
        c.gravity = {0, -10};
        c.air_density = 0;
        c.substeps = 4;
        world w(c, 0);
        body_material ground;
        ground.restitution = 0;  // restitution mixes as the larger of the two: the ball's
        REQUIRE(w.add_chain(std::vector<vec2>{{-10, 0}, {10, 0}}, ground));
        body_material m;
        m.radius = 0.5f;
        m.restitution = e;
        const uint32_t id = *w.add_body(make_body(m, {0.3f, 5}));
        // Falling until the step that turns it round; the speed it started that step with is
        // the impact speed, the speed it ended it with is the rebound.
        real impact = 0, rebound = 0;
        for (int k = 0; k < 120 && rebound == 0; ++k) {
            const real before = w.find(id)->velocity.y();
            w.step({});
            const real after = w.find(id)->velocity.y();
            if (before < 0 && after > 0) {
                impact = -before;
                rebound = after;
            }
        }
        INFO("e " << e);
        REQUIRE(impact > 9);  // √(2·10·4.5) ≈ 9.5 m/s
        CHECK(rebound == Approx(e * impact).epsilon(0.03));
    }
}

TEST_CASE("a sub-stepped world is the same for the same config, tick by tick", "[world][substeps][determinism]") {
    for (world_config c : {platformer_preset(), asteroids_preset(), pyramid_preset(12)}) {
        c.substeps = 4;
        world a(c, 42), b(c, 42);
        for (int k = 0; k < 300; ++k) {
            a.step({});
            b.step({});
            REQUIRE(a.hash() == b.hash());
        }
        // Something moved: the hash is of a world that did something.
        CHECK(a.hash() != world(c, 42).hash());
    }
}

TEST_CASE("one sub-step is the one-step solver, bit for bit", "[world][substeps][determinism]") {
    // The hash the one-step solver gave before sub-steps existed: `arena-sim --preset pyramid
    // --base 10 --steps 120`, when the preset did not sub-step.
    world_config c = pyramid_preset(10);
    c.substeps = 1;
    world w(c, 1);
    for (int k = 0; k < 120; ++k) w.step({});
    CHECK(w.hash() == 0xf1f440f09e0f17f9ull);
}

TEST_CASE("sub-steps change the results", "[world][substeps]") {
    world_config one = pyramid_preset(10), four = pyramid_preset(10);
    one.substeps = 1;
    four.substeps = 4;
    world a(one, 1), b(four, 1);
    for (int k = 0; k < 60; ++k) {
        a.step({});
        b.step({});
    }
    CHECK(a.hash() != b.hash());
}

TEST_CASE("a head-on impact in sub-steps gives one event with the impulse of the whole step", "[world][substeps]") {
    world_config c;
    c.air_density = 0;
    c.substeps = 4;
    world w(c, 1);
    w.set_contact_events(true);
    body_material m;
    m.mass = 1;
    m.radius = 0.5f;
    m.restitution = 0.5f;
    m.friction = 0;
    // 0.125 m apart, closing at 2 m/s: they overlap at the fifth detection.
    body left = make_body(m, {10, 10}), right = make_body(m, {11.125f, 10});
    left.velocity = {1, 0};
    right.velocity = {-1, 0};
    const uint32_t a = *w.add_body(left);
    const uint32_t b = *w.add_body(right);
    std::vector<contact_event> seen;
    for (int k = 0; k < 30; ++k) {
        w.step({});
        for (const contact_event& e : w.contact_events()) seen.push_back(e);
    }
    REQUIRE(seen.size() == 1);
    CHECK(seen[0].a == a);
    CHECK(seen[0].b == b);
    CHECK(seen[0].approach_speed == Approx(2.0f));
    // Equal masses of 1 kg: effective mass 1/2, impulse (1 + e)·m_eff·v_rel = 1.5·0.5·2, summed
    // over the sub-steps; each ball leaves at e·1 m/s.
    CHECK(seen[0].impulse == Approx(1.5f).epsilon(1e-3));
    CHECK(w.find(a)->velocity.x() == Approx(-0.5f).epsilon(1e-3));
    CHECK(w.find(b)->velocity.x() == Approx(0.5f).epsilon(1e-3));
}
