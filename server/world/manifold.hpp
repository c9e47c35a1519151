#pragma once
// The narrow phase: where two shapes touch, as at most two contact points sharing one normal.
//
// Design after Box2D v3's manifold functions (our own code): separating axis over the edge
// normals, the reference edge (the axis of least penetration, with a tolerance so that the
// choice does not flicker), the incident edge clipped against the reference edge's side planes,
// and points kept while they are within the speculative distance. Each point carries a feature
// id (which vertex or edge of each shape made it), so that the solver can warm-start it from
// the previous step's impulse when the same features touch again.
#include <cstdint>

#include "server/world/shape.hpp"
#include "server/world/types.hpp"

namespace arena::world {

// A body's place: its position and its rotation as (cos, sin).
struct transform {
    vec2 p{0, 0};  // m
    real c = 1;    // cos of the angle
    real s = 0;    // sin of the angle

    vec2 apply(const vec2& v) const { return {c * v.x() - s * v.y() + p.x(), s * v.x() + c * v.y() + p.y()}; }
    vec2 rotate(const vec2& v) const { return {c * v.x() - s * v.y(), s * v.x() + c * v.y()}; }
};

struct manifold_point {
    vec2 point{0, 0};     // m, world frame: midway between the two surfaces
    real separation = 0;  // m, negative when overlapping
    uint16_t id = 0;      // feature id, unique within the manifold
};

struct manifold {
    vec2 normal{1, 0};  // unit, from a towards b
    uint8_t count = 0;  // 0, 1 or 2
    manifold_point points[2];
};

// Shape a at xa against shape b at xb. Points farther apart than `speculative` are left out.
manifold collide(const shape& a, const transform& xa, const shape& b, const transform& xb, real speculative);

// Shape a against the half-space wall {x : normal·x ≥ offset}, normal pointing from the body
// into the wall: up to the two deepest vertices.
manifold collide_wall(const shape& a, const transform& xa, const vec2& normal, real offset, real speculative);

// Hull a (2 to 8 vertices) against edge `edge` of hull b taken as the reference face, whatever
// the separating axis would say: a's edge that faces it most, clipped to the edge's extent.
// The normal (b's edge normal, negated) points from a to b; the feature ids are those
// collide_hulls gives when it picks that edge. Chains snap to their face with it.
manifold collide_on_edge(const shape& a, const transform& xa, const shape& b, const transform& xb, int edge,
                         real speculative);

// The pairs, for tests and for callers that know the kinds.
manifold collide_circles(const vec2& ca, real ra, const vec2& cb, real rb, real speculative);
manifold collide_hull_circle(const shape& a, const transform& xa, const vec2& centre, real radius, real speculative);
manifold collide_hulls(const shape& a, const transform& xa, const shape& b, const transform& xb, real speculative);
// The same, for shapes already turned (turned_shape, shape.hpp) with their bodies at pa and pb.
manifold collide_hulls(const turned_shape& a, const vec2& pa, const turned_shape& b, const vec2& pb, real speculative);

}  // namespace arena::world
