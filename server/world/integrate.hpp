#pragma once
// Euler integration of one body over Δt: velocities from the accumulated forces, positions
// from velocities. Semi-implicit Euler runs velocities then positions; explicit Euler runs
// positions (with the old velocity) then velocities.
#include "server/world/body.hpp"

namespace arena::world {

// v += (F/m)·Δt and ω += (τ/I)·Δt, then the resistance (friction, drag, damping), which may
// bring a component of velocity to exactly zero but never reverse it.
void integrate_velocity(body& b, real dt);

// x += v·Δt and θ += ω·Δt (θ wrapped into (−π, π]).
void integrate_position(body& b, real dt);

}  // namespace arena::world
