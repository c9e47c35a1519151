#pragma once
// One body, one scenario: the lecture's experiments (constant force, free fall, friction, drag)
// run through the real world code, so they can be checked against a hand calculation.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "server/world/config.hpp"

namespace arena::sim {

struct single_body_scenario {
    world::real dt = 1.0f;  // s
    uint32_t steps = 10;
    world::real mass = 1.0f;              // kg
    world::vec2 force{0, 0};              // N, applied every step
    world::vec2 velocity{0, 0};           // m/s, initial
    world::vec2 gravity{0, 0};            // m/s²
    world::real friction = 0.0f;          // μ: the body slides on a floor, N = m·|g|
    world::real density = 0.0f;           // kg/m³ of the medium (0: no drag)
    world::real drag_coefficient = 0.0f;  // Cd
    world::real area = 0.0f;              // m², frontal area A
    world::integrator integrator = world::integrator::semi_implicit;
};

struct sample {
    world::real t, x, y, vx, vy, angle, omega;
};

// Most steps of one scenario: every step is a row kept in memory and printed (4e9 steps
// asked for 112 GB and aborted on bad_alloc). A million rows is hours of simulated time.
inline constexpr uint32_t max_scenario_steps = 1'000'000;

// Why the scenario cannot run as asked, or nothing.
std::optional<std::string> check_scenario(const single_body_scenario& s);

// The body's state after each step (steps rows; t = k·dt).
std::vector<sample> run_scenario(const single_body_scenario& s);

// The exact solution at time t when the acceleration is constant (no friction, no drag).
std::optional<sample> exact_solution(const single_body_scenario& s, double t);

}  // namespace arena::sim
