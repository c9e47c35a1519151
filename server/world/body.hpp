#pragma once
// A rigid body: a circle of `radius` unless `shape` names a shape in its world's pool
// (shape.hpp). Forces accumulate between steps and are cleared after each step; impulses
// change velocity at once (Δv = J/m, the lecture's impulse). Static bodies have zero inverse
// mass and inverse inertia.
#include <cstdint>
#include <optional>
#include <string>

#include "server/world/config.hpp"
#include "server/world/filter.hpp"
#include "server/world/shape.hpp"
#include "server/world/types.hpp"

namespace arena::world {

// body::shape of a circle: its radius is all there is to it.
inline constexpr uint32_t no_shape = ~0u;

struct body {
    uint32_t id = 0;                // unique in its world, never reused; bodies are kept in id order
    uint32_t owner = 0;             // player id that controls it; 0 = nobody
    real mass = 1.0f;               // kg
    real inv_mass = 1.0f;           // 1/kg, 0 = static
    real inertia = 0.5f;            // kg·m², moment of inertia about the centre
    real inv_inertia = 2.0f;        // 1/(kg·m²), 0 = never rotates
    real radius = 1.0f;             // m, a circle's radius; any other shape's bounding radius
    real restitution = 0.5f;        // [0, 1]
    real friction = 0.6f;           // μ, Coulomb friction at its contacts (mixed: √(μa·μb))
    real drag_area = 0.0f;          // m², A·Cd
    vec2 position{0, 0};            // m
    vec2 velocity{0, 0};            // m/s
    real angle = 0.0f;              // rad, in (−π, π]; facing = (cos, sin)
    real angular_velocity = 0.0f;   // rad/s, counter-clockwise
    vec2 force{0, 0};               // N, accumulated this step (thrust, gravity, normal force, user)
    real torque = 0.0f;             // N·m, accumulated this step
    vec2 resistance{0, 0};          // N, friction and drag this step: may stop the body, never reverse it
    real resistance_torque = 0.0f;  // N·m, angular damping this step, same rule
    uint32_t impulse_cooldown = 0;  // ticks until button 0 may fire again
    uint32_t shape = no_shape;      // index in the world's shape pool (set by world::add_body)
    collision_filter filter{};      // which bodies it collides with (walls ignore it)

    void apply_force(const vec2& f) { force += f; }
    void apply_torque(real t) { torque += t; }
    void apply_impulse(const vec2& j) { velocity += j * inv_mass; }
    void apply_angular_impulse(real j) { angular_velocity += j * inv_inertia; }
    bool is_static() const { return inv_mass == 0.0f; }
};

// A circle made of `material`, at rest at `position`. Mass from density·π·r² unless given.
body make_body(const body_material& material, const vec2& position);
// A body of shape `s` (centred on its centre of mass, as the shape makers give it) made of
// `material` (its radius ignored): mass and inertia from the shape and the density, or the
// given mass with the shape's inertia scaled to it. Add it with world::add_body(b, s).
body make_body(const body_material& material, const shape& s, const vec2& position);

// The shape a config describes (not a chain: world::add_chain makes those), centred on its
// centre of mass, with that centre in the config's body frame; or the reason it cannot be one,
// naming the config field ("points", "half_extents", ...).
result<centred_shape> make_shape(const shape_config& config);

}  // namespace arena::world
