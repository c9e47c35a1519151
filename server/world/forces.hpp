#pragma once
// The forces of the lecture, accumulated into a body for one step: weight, thrust and torque
// from a player's input, the floor's normal force and kinetic friction, and quadratic drag.
#include "server/world/body.hpp"
#include "server/world/config.hpp"
#include "server/world/input.hpp"

namespace arena::world {

// Thrust along the facing (or +x), torque, and the button-0 impulse if its cooldown allows.
void apply_player_input(body& b, const player_input& input, const control_config& control, bool on_ground);

// Weight m·g.
void apply_weight(body& b, const vec2& gravity);

// On the floor: the normal force N = m·max(0, −g_y) cancels the weight's downward part, and
// kinetic friction −μ·N·sign(vx) opposes sliding (as resistance: it stops, never reverses).
void apply_floor_contact(body& b, const vec2& gravity, real friction);

// Quadratic drag −½·ρ·|v|²·(A·Cd)·v̂ in a medium of density `rho` (as resistance).
void apply_drag(body& b, real rho);

// −damping·I·ω (as resistance torque).
void apply_angular_damping(body& b, real damping);

// Density of the medium at `position`: the first fluid region containing it, else the air.
real medium_density(const world_config& config, const vec2& position);

}  // namespace arena::world
