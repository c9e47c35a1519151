// The lecture's worked example (../shared/seed): constant 10 N on 1 kg, Δt = 1 s, 10 steps.
#include <catch2/catch.hpp>
#include <cmath>

#include "server/world/world.hpp"

using namespace arena::world;

namespace {

struct run_result {
    real x, v;
};

run_result push_for_10_seconds(integrator method, real dt) {
    world_config config;
    config.dt = dt;
    config.integrator = method;
    config.air_density = 0;
    world w(config, 0);
    body_material m;
    m.mass = 1;
    const uint32_t id = *w.add_body(make_body(m, {0, 0}));
    const int steps = static_cast<int>(std::lround(10.0 / dt));
    for (int k = 0; k < steps; ++k) {
        w.find(id)->apply_force({10, 0});
        w.step({});
    }
    return {w.find(id)->position.x(), w.find(id)->velocity.x()};
}

}  // namespace

TEST_CASE("explicit Euler reproduces the lecture's table: 450 m and 100 m/s", "[world][lecture]") {
    const run_result r = push_for_10_seconds(integrator::explicit_euler, 1.0f);
    CHECK(r.x == 450.0f);
    CHECK(r.v == 100.0f);
}

TEST_CASE("semi-implicit Euler overshoots to 550 m on the lecture's example", "[world][lecture]") {
    const run_result r = push_for_10_seconds(integrator::semi_implicit, 1.0f);
    CHECK(r.x == 550.0f);
    CHECK(r.v == 100.0f);
}

TEST_CASE("both Euler errors shrink linearly with the time step", "[world][lecture]") {
    const real exact = 500.0f;
    for (integrator method : {integrator::explicit_euler, integrator::semi_implicit}) {
        const real e1 = std::fabs(push_for_10_seconds(method, 1.0f).x - exact);
        const real e2 = std::fabs(push_for_10_seconds(method, 0.5f).x - exact);
        const real e4 = std::fabs(push_for_10_seconds(method, 0.25f).x - exact);
        CHECK(e1 == Approx(50.0f));
        CHECK(e1 / e2 == Approx(2.0f).epsilon(1e-3));
        CHECK(e2 / e4 == Approx(2.0f).epsilon(1e-3));
    }
}
