#include "server/world/body.hpp"

#include "server/world/trig.hpp"

namespace arena::world {

body make_body(const body_material& material, const vec2& position) {
    body b;
    b.radius = material.radius;
    b.mass = material.mass > 0 ? material.mass : material.density * pi * material.radius * material.radius;
    b.inv_mass = b.mass > 0 ? 1.0f / b.mass : 0.0f;
    // A uniform disc: I = ½·m·r².
    b.inertia = 0.5f * b.mass * b.radius * b.radius;
    b.inv_inertia = (material.fixed_rotation || b.inertia <= 0) ? 0.0f : 1.0f / b.inertia;
    b.restitution = material.restitution;
    b.drag_area = material.drag_area;
    b.position = position;
    return b;
}

}  // namespace arena::world
