#include "server/world/integrate.hpp"

#include "server/world/forces.hpp"

namespace arena::world {

void integrate_free_bodies(std::span<body> bodies, const world_config& config) {
    const real dt = config.dt;
    for (body& stored : bodies) {
        // On a copy, stored back once: see the note on local copies in integrate.hpp.
        body b = stored;
        accumulate_forces(b, config);
        if (config.integrator == integrator::explicit_euler) integrate_position(b, dt);  // old velocity
        integrate_velocity(b, dt);
        if (config.integrator == integrator::semi_implicit) integrate_position(b, dt);  // new velocity
        wrap_position(b, config);
        clear_accumulators(b);
        stored = b;
    }
}

}  // namespace arena::world
