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

std::optional<shape> make_shape(const shape_config& c, std::string& error, vec2& centre) {
    centre = {0, 0};
    switch (c.type) {
        case shape_type::circle:
            if (!(c.radius > 0)) break;
            return make_circle(c.radius);
        case shape_type::capsule:
            if (!(c.radius > 0)) break;
            if (!(c.half_length > 0)) {
                error = "'half_length' must be positive";
                return std::nullopt;
            }
            return make_capsule(c.half_length, c.radius);
        case shape_type::box:
            if (!(c.half_extents.x() > 0 && c.half_extents.y() > 0)) {
                error = "'half_extents' must be positive";
                return std::nullopt;
            }
            if (!(c.rounding >= 0)) {
                error = "'rounding' must not be negative";
                return std::nullopt;
            }
            return make_box(c.half_extents.x(), c.half_extents.y(), c.rounding);
        case shape_type::polygon: {
            if (!(c.rounding >= 0)) {
                error = "'rounding' must not be negative";
                return std::nullopt;
            }
            polygon_result r = make_polygon(c.points, c.rounding);
            if (!r.polygon) {
                error = "'points': " + r.error;
                return std::nullopt;
            }
            centre = r.centroid;
            return r.polygon;
        }
        case shape_type::segment:
            if (c.points.size() != 2 || c.points[0] == c.points[1]) {
                error = "'points' must be two distinct points";
                return std::nullopt;
            }
            return make_segment(c.points[0], c.points[1]);
        case shape_type::chain:
            error = "a chain is several bodies";
            return std::nullopt;
    }
    error = "'radius' must be positive";
    return std::nullopt;
}

}  // namespace arena::world
