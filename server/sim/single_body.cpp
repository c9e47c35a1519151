#include "server/sim/single_body.hpp"

#include <cmath>

#include "server/world/world.hpp"

namespace arena::sim {

using world::real;
using world::vec2;

std::optional<std::string> check_scenario(const single_body_scenario& s) {
    if (!(s.dt > 0)) return "--dt must be positive";
    if (s.steps > max_scenario_steps)
        return "--steps must be at most " + std::to_string(max_scenario_steps) +
               " for one body (one row per step), got " + std::to_string(s.steps);
    if (!(s.mass > 0)) return "--mass must be positive";
    if (s.friction < 0 || s.density < 0 || s.drag_coefficient < 0 || s.area < 0)
        return "--friction, --density, --drag-coefficient and --area must not be negative";
    if (s.friction > 0 && !(s.gravity.y() < 0))
        return "--friction needs a floor to slide on: give --gravity pointing down, e.g. --gravity 0,-9.81";
    return std::nullopt;
}

std::vector<sample> run_scenario(const single_body_scenario& s) {
    world::world_config config;
    config.dt = s.dt;
    config.integrator = s.integrator;
    config.gravity = s.gravity;
    config.air_density = s.density;
    // With friction the body slides on the floor y = 0; otherwise space is open.
    config.boundary = s.friction > 0 ? world::boundary::floor : world::boundary::open;
    config.floor_friction = s.friction;
    world::world w(config, 0);

    world::body_material material;
    material.mass = s.mass;
    material.radius = 0;  // a point mass: it stands on the floor at y = 0
    material.drag_area = s.area * s.drag_coefficient;
    world::body b = world::make_body(material, {0, 0});
    b.velocity = s.velocity;
    const uint32_t id = *w.add_body(b);

    std::vector<sample> rows;
    rows.reserve(s.steps);
    for (uint32_t k = 1; k <= s.steps; ++k) {
        w.find(id)->apply_force(s.force);
        w.step({});
        const world::body& now = *w.find(id);
        rows.push_back({static_cast<real>(k) * s.dt, now.position.x(), now.position.y(), now.velocity.x(),
                        now.velocity.y(), now.angle, now.angular_velocity});
    }
    return rows;
}

std::optional<sample> exact_solution(const single_body_scenario& s, double t) {
    if (s.friction > 0 || (s.density > 0 && s.area > 0 && s.drag_coefficient > 0)) return std::nullopt;
    const double ax = static_cast<double>(s.force.x()) / s.mass + s.gravity.x();
    const double ay = static_cast<double>(s.force.y()) / s.mass + s.gravity.y();
    auto at = [t](double v0, double a) {
        return v0 * t + 0.5 * a * t * t;
    };
    return sample{static_cast<real>(t),
                  static_cast<real>(at(s.velocity.x(), ax)),
                  static_cast<real>(at(s.velocity.y(), ay)),
                  static_cast<real>(s.velocity.x() + ax * t),
                  static_cast<real>(s.velocity.y() + ay * t),
                  0,
                  0};
}

}  // namespace arena::sim
