#include "server/match/shape_wire.hpp"

namespace arena::match {

protocol::shape_desc describe(const world::world& w, const world::body& b, uint8_t kind) {
    protocol::shape_desc d;
    d.id = b.id;
    d.kind = kind;
    const world::shape s = w.shape_of(b);
    switch (s.kind) {
        case world::shape_kind::circle:
            d.type = protocol::ShapeType::circle;
            break;
        case world::shape_kind::capsule:
            d.type = protocol::ShapeType::capsule;
            break;
        case world::shape_kind::polygon:
            d.type = protocol::ShapeType::polygon;
            break;
        case world::shape_kind::segment:
            d.type = protocol::ShapeType::segment;
            break;
    }
    d.vertex_count = s.count;
    d.radius = s.radius;
    for (unsigned i = 0; i < s.count; ++i) {
        d.xy[2 * i] = s.vertices[i].x();
        d.xy[2 * i + 1] = s.vertices[i].y();
    }
    return d;
}

std::vector<protocol::static_body> static_geometry(const world::world& w, const body_kinds& kinds) {
    std::vector<protocol::static_body> out;
    for (const world::body& b : w.bodies()) {
        if (!b.is_static()) continue;
        out.push_back({b.position.x(), b.position.y(), b.angle, describe(w, b, kinds.of(b.id))});
    }
    return out;
}

}  // namespace arena::match
