#pragma once
// Collision shapes: one per body, in the body's frame (its origin is the body's centre of mass,
// so that rotation turns a body about that point).
//
// Every shape is a rounded convex hull: a core of 1 to 8 vertices, swept by a disc of `radius`.
//   circle   1 vertex (the centre), radius r
//   capsule  2 vertices (the ends of its axis), radius r
//   polygon  3 to 8 vertices, counter-clockwise, optional rounding radius (boxes: make_box)
//   segment  2 vertices, radius 0: static level geometry (world::add_chain builds a run of them,
//            each linked to its neighbours: chain_link)
// One representation keeps the narrow phase to three routines (manifold.hpp), as Box2D v3
// treats its capsules as two-vertex polygons.
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "server/world/result.hpp"
#include "server/world/types.hpp"

namespace arena::world {

enum class shape_kind : uint8_t { circle, capsule, polygon, segment };

inline constexpr int max_polygon_vertices = 8;

// What a chain's segment knows of its chain (Box2D v3's ghost vertices): the points before and
// after it, so that a body sliding along the chain does not catch on the joints, and the side
// it is solid on. A chain is one-sided: bodies collide with the face on the left of its
// direction (edge 1 of the segment, vertices[1] → vertices[0], normal normals[1]), so a floor
// runs left to right and a loop listed clockwise is solid. chain_manifold.hpp uses it.
struct chain_link {
    bool linked = false;    // a chain's segment; false: a free segment, solid on both sides
    bool has_prev = false;  // the chain goes on before vertices[0]
    bool has_next = false;  // the chain goes on after vertices[1]
    vec2 prev{0, 0};        // m, body frame: the chain's point before vertices[0]
    vec2 next{0, 0};        // m, body frame: the chain's point after vertices[1]
};

struct shape {
    // Eigen leaves its vectors uninitialised: zero them, so that unused entries hash and
    // compare the same everywhere.
    shape() {
        vertices.fill(vec2{0, 0});
        normals.fill(vec2{0, 0});
    }

    shape_kind kind = shape_kind::circle;
    uint8_t count = 1;                                  // core vertices
    real radius = 1.0f;                                 // m, the rounding (a circle's or capsule's radius)
    std::array<vec2, max_polygon_vertices> vertices{};  // m, body frame, counter-clockwise
    std::array<vec2, max_polygon_vertices> normals{};   // outward unit normal of edge i → i+1
    chain_link chain{};                                 // segments of a chain only
};

// Mass properties of a shape of uniform density (kg/m², 2D).
struct mass_properties {
    real mass = 0;      // kg
    vec2 centre{0, 0};  // m, centre of mass in the frame the vertices were given in
    real inertia = 0;   // kg·m², about the centre of mass
};

shape make_circle(real radius);
// A capsule whose axis runs from −half_length to +half_length along x (its body frame).
shape make_capsule(real half_length, real radius);
// A box of half extents (hx, hy), optionally rounded (its outline grows by `radius`).
shape make_box(real hx, real hy, real radius = 0);
// A segment from `a` to `b` in the body frame (its body sits at the midpoint: make_segment_at).
shape make_segment(const vec2& a, const vec2& b);

// A shape centred on its centre of mass, and where that centre lies in the frame the shape was
// described in (a polygon's centroid; 0 for the others): the body goes there.
struct centred_shape {
    shape geometry;
    vec2 centre{0, 0};
};

// A convex polygon from up to 8 points in any order (their convex hull, counter-clockwise),
// shifted so that its centroid is the origin (`centre`: the shift). The reason when the points
// have no area (fewer than 3 distinct, collinear) or there are more than 8.
result<centred_shape> make_polygon(std::span<const vec2> points, real radius = 0);

// Exact for circles, capsules and polygons; a rounded polygon adds its edge strips and corner
// sectors, exact when its corners are equal (boxes, regular polygons), otherwise the sectors'
// masses are shared equally (an error of order r² in the mass distribution).
mass_properties compute_mass(const shape& s, real density);

// The largest distance from the body's origin to the shape's outline (m): the bounding circle.
real bounding_radius(const shape& s);

// An axis-aligned box.
struct aabb {
    vec2 lo{0, 0};
    vec2 hi{0, 0};
};

// The shape's box with the body at `position`, turned by (c, s).
aabb compute_aabb(const shape& sh, const vec2& position, real c, real s);

// A shape turned by (c, s), not yet placed: its vertices and normals in world directions. The
// broadphase turns each body's shape once a step; a pair in the narrow phase then only adds
// the two positions. Turning then adding is the very arithmetic of turning and placing in one
// go ((c·x − s·y) + p), so both give the same bits.
struct turned_shape {
    int count = 0;  // first: read with the first vertices, in one cache line
    real radius = 0;
    std::array<vec2, max_polygon_vertices> vertices;  // m, only the first `count` are set
    std::array<vec2, max_polygon_vertices> normals;
};

turned_shape turn(const shape& sh, real c, real s);
// The turned shape's box with the body at `position`: compute_aabb's, bit for bit.
aabb compute_aabb(const turned_shape& sh, const vec2& position);

}  // namespace arena::world
