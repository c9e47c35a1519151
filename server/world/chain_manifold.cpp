#include "server/world/chain_manifold.hpp"

#include <cmath>

namespace arena::world {

namespace {

// sin of the least bend that makes a joint convex (0.57°): flatter joints count as flat, so that
// a run of nearly collinear points slides like one segment.
constexpr real convex_tolerance = 0.01f;
// sin of the angle within which a normal is the segment's own face normal: left as it is.
constexpr real face_tolerance = 0.01f;
// m: a circle this close to the boundary between two segments' regions is collided by both, so
// that rounding in their two positions cannot leave it to neither (it would fall through).
constexpr real region_overlap = 0.001f;

real cross(const vec2& a, const vec2& b) {
    return a.x() * b.y() - a.y() * b.x();
}

vec2 unit(const vec2& v) {
    return v / std::sqrt(v.squaredNorm());
}

// The left normal of a direction: a chain's solid face.
vec2 left_of(const vec2& e) {
    return {-e.y(), e.x()};
}

// The segment and its neighbours in world coordinates.
struct joint_view {
    vec2 p1{0, 0}, p2{0, 0};  // m, the segment's ends
    vec2 e1{0, 0};            // unit, p1 → p2
    vec2 n1{0, 0};            // the solid face's normal (left of e1)
    vec2 e0{0, 0}, n0{0, 0};  // the previous segment's direction and normal (has_prev)
    vec2 n2{0, 0};            // the next segment's normal (has_next)
    bool has_prev = false;
    bool has_next = false;
    bool convex1 = false;  // the joint at p1 turns away from the solid side
    bool convex2 = false;  // the joint at p2 does
};

joint_view view_of(const shape& s, const transform& xs) {
    joint_view j;
    j.p1 = xs.apply(s.vertices[0]);
    j.p2 = xs.apply(s.vertices[1]);
    j.e1 = unit(j.p2 - j.p1);
    j.n1 = xs.rotate(s.normals[1]);
    j.has_prev = s.chain.has_prev;
    j.has_next = s.chain.has_next;
    if (j.has_prev) {
        j.e0 = unit(j.p1 - xs.apply(s.chain.prev));
        j.n0 = left_of(j.e0);
        j.convex1 = cross(j.e0, j.e1) <= -convex_tolerance;  // a right turn, seen from the left
    }
    if (j.has_next) {
        const vec2 e2 = unit(xs.apply(s.chain.next) - j.p2);
        j.n2 = left_of(e2);
        j.convex2 = cross(j.e1, e2) <= -convex_tolerance;
    }
    return j;
}

// A circle belongs to the segment whose region (face or joint) holds its centre: before p1,
// the previous face's unless the centre is past that face's end too (then the joint is this
// segment's); past p2, the next segment's.
manifold collide_circle(const joint_view& j, const shape& a, const transform& xa, const shape& segment,
                        const transform& xs, real speculative) {
    const vec2 c = xa.apply(a.vertices[0]);
    if (j.n1.dot(c - j.p1) < 0) return {};  // behind: one-sided
    if (j.has_prev && j.e1.dot(c - j.p1) < 0 && j.e0.dot(c - j.p1) < -region_overlap) return {};
    if (j.has_next && j.e1.dot(c - j.p2) > region_overlap) return {};
    return collide(a, xa, segment, xs, speculative);
}

manifold collide_hull(const joint_view& j, const shape& a, const transform& xa, const shape& segment,
                      const transform& xs, real speculative) {
    // One-sided: a body behind the face, and behind the faces of the convex neighbours (round
    // a convex joint the neighbour's side still counts as the front), does not collide.
    const vec2 c = xa.p;
    const bool behind1 = j.n1.dot(c - j.p1) < 0;
    const bool behind0 = !j.convex1 || j.n0.dot(c - j.p1) < 0;
    const bool behind2 = !j.convex2 || j.n2.dot(c - j.p2) < 0;
    if (behind1 && behind0 && behind2) return {};
    const manifold m = collide(a, xa, segment, xs, speculative);
    if (m.count == 0) return m;
    const vec2 n = -m.normal;  // from the segment to a
    const real along = n.dot(j.e1);
    if (std::abs(along) <= face_tolerance) return m;
    const bool tail = along < 0;                     // leaning towards p1, the previous segment
    if (tail ? !j.has_prev : !j.has_next) return m;  // the chain's free end: rounded, as a segment's
    // A flat or concave joint: a normal leaning into it comes from the next segment's end
    // hidden under the body (the catch): the face is the contact.
    if (!(tail ? j.convex1 : j.convex2)) return collide_on_edge(a, xa, segment, xs, 1, speculative);
    // A convex joint: the normal is the neighbour's when it lies nearer the neighbour's face
    // normal than this one's (so exactly one of the two keeps it, but on a tie).
    const vec2& neighbour = tail ? j.n0 : j.n2;
    if (neighbour.dot(n) > j.n1.dot(n)) return {};
    return m;
}

}  // namespace

manifold collide_chain_segment(const shape& a, const transform& xa, const shape& segment, const transform& xs,
                               real speculative) {
    const joint_view j = view_of(segment, xs);
    if (a.count == 1) return collide_circle(j, a, xa, segment, xs, speculative);
    return collide_hull(j, a, xa, segment, xs, speculative);
}

}  // namespace arena::world
