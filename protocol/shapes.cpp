#include "protocol/shapes.hpp"

#include <cmath>

namespace arena::protocol {
namespace {

// The vertex counts a type allows; a type this library does not know (a newer server's)
// passes with any count it can hold, so that its neighbours still line up.
bool count_fits(ShapeType type, unsigned count) {
    switch (type) {
        case ShapeType::circle:
            return count == 1;
        case ShapeType::capsule:
        case ShapeType::segment:
            return count == 2;
        case ShapeType::polygon:
            return count >= 3 && count <= max_shape_vertices;
    }
    return count >= 1 && count <= max_shape_vertices;
}

}  // namespace

void shape_list::append(const shape_desc& d) {
    shapes.emplace_back(d.id, d.kind, d.type, d.vertex_count, d.radius);
    for (unsigned i = 0; i < d.vertex_count; ++i) vertices.emplace_back(d.xy[2 * i], d.xy[2 * i + 1]);
}

std::string read_shapes(const flatbuffers::Vector<const BodyShape*>* shapes,
                        const flatbuffers::Vector<const ShapeVertex*>* vertices, std::vector<shape_desc>& out) {
    const std::size_t shape_count = shapes == nullptr ? 0 : shapes->size();
    const std::size_t vertex_count = vertices == nullptr ? 0 : vertices->size();
    const std::size_t first = out.size();
    std::size_t next_vertex = 0;
    for (std::size_t i = 0; i < shape_count; ++i) {
        const BodyShape& s = *shapes->Get(static_cast<flatbuffers::uoffset_t>(i));
        const std::string where = "shape " + std::to_string(i) + " (body " + std::to_string(s.id()) + ")";
        std::string problem;
        if (!count_fits(s.shape_type(), s.vertex_count())) {
            problem = where + ": " + std::to_string(s.vertex_count()) + " vertices do not fit its type " +
                      std::to_string(static_cast<unsigned>(s.shape_type()));
        } else if (!std::isfinite(s.radius()) || s.radius() < 0) {
            problem = where + ": radius is not a finite number ≥ 0";
        } else if (vertex_count - next_vertex < s.vertex_count()) {
            problem = where + ": the shapes name more vertices than the " + std::to_string(vertex_count) + " given";
        }
        shape_desc d;
        d.id = s.id();
        d.kind = s.kind();
        d.type = s.shape_type();
        d.vertex_count = s.vertex_count();
        d.radius = s.radius();
        for (unsigned v = 0; problem.empty() && v < d.vertex_count; ++v) {
            const ShapeVertex& p = *vertices->Get(static_cast<flatbuffers::uoffset_t>(next_vertex++));
            if (!std::isfinite(p.x()) || !std::isfinite(p.y())) problem = where + ": a vertex is not finite";
            d.xy[2 * v] = p.x();
            d.xy[2 * v + 1] = p.y();
        }
        if (!problem.empty()) {
            out.resize(first);
            return problem;
        }
        out.push_back(d);
    }
    if (next_vertex != vertex_count) {
        out.resize(first);
        return "the shapes name " + std::to_string(next_vertex) + " vertices, " + std::to_string(vertex_count) +
               " are given";
    }
    return {};
}

}  // namespace arena::protocol
