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
    b.friction = material.friction;
    b.drag_area = material.drag_area;
    b.position = position;
    return b;
}

body make_body(const body_material& material, const shape& s, const vec2& position) {
    body b;
    const mass_properties m = compute_mass(s, material.density > 0 ? material.density : 1.0f);
    b.radius = s.kind == shape_kind::circle ? s.radius : bounding_radius(s);
    const bool is_static = material.density <= 0 && material.mass <= 0;
    b.mass = is_static ? 0.0f : material.mass > 0 ? material.mass : m.mass;
    b.inv_mass = b.mass > 0 ? 1.0f / b.mass : 0.0f;
    b.inertia = m.mass > 0 ? m.inertia * (b.mass / m.mass) : 0.0f;
    b.inv_inertia = (material.fixed_rotation || b.inertia <= 0) ? 0.0f : 1.0f / b.inertia;
    b.restitution = material.restitution;
    b.friction = material.friction;
    b.drag_area = material.drag_area;
    b.position = position;
    return b;
}

}  // namespace arena::world

namespace arena::world {

result<centred_shape> make_shape(const shape_config& c) {
    using made = result<centred_shape>;
    switch (c.type) {
        case shape_type::circle:
            if (!(c.radius > 0)) break;
            return made::success({make_circle(c.radius)});
        case shape_type::capsule:
            if (!(c.radius > 0)) break;
            if (!(c.half_length > 0)) return made::failure("'half_length' must be positive");
            return made::success({make_capsule(c.half_length, c.radius)});
        case shape_type::box:
            if (!(c.half_extents.x() > 0 && c.half_extents.y() > 0))
                return made::failure("'half_extents' must be positive");
            if (!(c.rounding >= 0)) return made::failure("'rounding' must not be negative");
            return made::success({make_box(c.half_extents.x(), c.half_extents.y(), c.rounding)});
        case shape_type::polygon: {
            if (!(c.rounding >= 0)) return made::failure("'rounding' must not be negative");
            made polygon = make_polygon(c.points, c.rounding);
            if (!polygon) polygon.error = "'points': " + polygon.error;
            return polygon;
        }
        case shape_type::segment:
            if (c.points.size() != 2 || c.points[0] == c.points[1])
                return made::failure("'points' must be two distinct points");
            return made::success({make_segment(c.points[0], c.points[1])});
        case shape_type::chain:
            return made::failure("a chain is several bodies");
    }
    return made::failure("'radius' must be positive");
}

}  // namespace arena::world
