#pragma once
// Body shapes on the wire (README.md, "Shapes"): a Snapshot describes each body of the view
// that the client may not hold yet, and the Welcome every static body. A description is one
// 12-byte BodyShape and its vertex_count ShapeVertex entries, which follow those of the
// previous description in a separate vector: no tables, so a client's verifier limits and
// the work of verifying stay what they were.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "protocol/arena_generated.h"

namespace arena::protocol {

inline constexpr std::uint8_t max_shape_vertices = 8;

// One body's shape as plain values.
struct shape_desc {
    std::uint32_t id = 0;
    std::uint8_t kind = 0;  // the game's appearance tag (ship, rock...); 0 = a plain body
    ShapeType type = ShapeType::circle;
    std::uint8_t vertex_count = 1;
    float radius = 0;                                // m
    std::array<float, 2 * max_shape_vertices> xy{};  // x0, y0, x1, y1, ... in the body's frame, m
    bool operator==(const shape_desc&) const = default;
};

// A static body of the Welcome: its pose and its shape.
struct static_body {
    float x = 0, y = 0;  // m
    float angle = 0;     // rad
    shape_desc shape;
    bool operator==(const static_body&) const = default;
};

// Descriptions laid out as the schema's two vectors, ready to encode, and the origins of the
// bullets among them (Snapshot.shot_origins: a bullet's origin travels with its shape).
struct shape_list {
    std::vector<BodyShape> shapes;
    std::vector<ShapeVertex> vertices;
    std::vector<ShotOrigin> origins;
    void clear() {
        shapes.clear();
        vertices.clear();
        origins.clear();
    }
    [[nodiscard]] bool empty() const { return shapes.empty(); }
    void append(const shape_desc& d);
    // Bytes these descriptions add to a message, FlatBuffers framing aside.
    [[nodiscard]] std::size_t wire_bytes() const {
        return shapes.size() * sizeof(BodyShape) + vertices.size() * sizeof(ShapeVertex) +
               origins.size() * sizeof(ShotOrigin);
    }
};

// Reads the descriptions of two vectors into `out` (appended). Checks what a client relies on
// to draw: the vertex counts add up to the vertices given, each count fits its type (circle 1,
// capsule and segment 2, polygon 3..8; a type from a newer server: 1..8), and every number is
// finite with a radius ≥ 0. The reason when not; `out` is then unchanged.
[[nodiscard]] std::string read_shapes(const flatbuffers::Vector<const BodyShape*>* shapes,
                                      const flatbuffers::Vector<const ShapeVertex*>* vertices,
                                      std::vector<shape_desc>& out);

}  // namespace arena::protocol
