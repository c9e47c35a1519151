#include "server/world/manifold.hpp"

#include <algorithm>
#include <cmath>

namespace arena::world {

namespace {

// Below this, two candidate reference axes count as equal and the first shape's wins, so that
// a resting box does not switch faces between steps (Box2D's 0.1 × linear slop).
constexpr real axis_tolerance = 0.0005f;

// A hull in world coordinates: a turned shape's vertices placed at p, its normals as they are
// (the turned shape outlives the hull).
struct world_hull {
    vec2 v[max_polygon_vertices];
    const vec2* n = nullptr;
    int count = 0;
    real radius = 0;
};

world_hull place(const turned_shape& t, const vec2& p) {
    world_hull h;
    h.count = t.count;
    h.radius = t.radius;
    h.n = t.normals.data();
    for (int i = 0; i < t.count; ++i) h.v[i] = t.vertices[i] + p;
    return h;
}

int next(const world_hull& h, int i) {
    return i + 1 < h.count ? i + 1 : 0;
}

// The edge of `a` along whose normal `b`'s core lies farthest out, and that distance.
real max_separation(const world_hull& a, const world_hull& b, int& edge) {
    real best = -3.4e38f;
    edge = 0;
    for (int i = 0; i < a.count; ++i) {
        real least = 3.4e38f;
        for (int j = 0; j < b.count; ++j) least = std::min(least, a.n[i].dot(b.v[j] - a.v[i]));
        if (least > best) {
            best = least;
            edge = i;
        }
    }
    return best;
}

// Closest points of the segments p1 + s·d1 and p2 + t·d2 (both of positive length), as the
// fractions s and t in [0, 1].
void closest_on_segments(const vec2& p1, const vec2& d1, const vec2& p2, const vec2& d2, real& s, real& t) {
    const vec2 r = p1 - p2;
    const real a = d1.squaredNorm(), e = d2.squaredNorm();
    const real b = d1.dot(d2), c = d1.dot(r), f = d2.dot(r);
    const real denom = a * e - b * b;
    s = denom > 0 ? std::clamp((b * f - c * e) / denom, real{0}, real{1}) : real{0};
    t = (b * s + f) / e;
    if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, real{0}, real{1});
    } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, real{0}, real{1});
    }
}

struct clip_vertex {
    vec2 x;
    uint16_t id;
};

// Keeps the part of the segment (v[0], v[1]) where dir·x ≥ offset; a new end takes `id`.
// False when nothing is left.
bool clip(clip_vertex v[2], const vec2& dir, real offset, uint16_t id) {
    const real d0 = dir.dot(v[0].x) - offset;
    const real d1 = dir.dot(v[1].x) - offset;
    if (d0 >= 0 && d1 >= 0) return true;
    if (d0 < 0 && d1 < 0) return false;
    const vec2 x = v[0].x + (v[1].x - v[0].x) * (d0 / (d0 - d1));
    if (d0 < 0) {
        v[0] = {x, id};
    } else {
        v[1] = {x, id};
    }
    return true;
}

// Feature ids: bit 9 says which shape holds the reference edge, bit 8 whether the point is an
// incident vertex (0) or the clip of the incident edge at a reference vertex (1), then the two
// feature indices, 4 bits each.
uint16_t feature_id(bool flip, bool clipped, int reference, int incident) {
    return static_cast<uint16_t>((flip ? 0x200 : 0) | (clipped ? 0x100 : 0) | (reference << 4) | incident);
}

// The incident edge: the one of the hull that faces the reference normal `n` most.
int incident_edge(const world_hull& inc, const vec2& n) {
    int edge = 0;
    real least = 3.4e38f;
    for (int i = 0; i < inc.count; ++i) {
        const real d = inc.n[i].dot(n);
        if (d < least) {
            least = d;
            edge = i;
        }
    }
    return edge;
}

// Edge i2 of `inc` clipped to the extent of the reference edge i1 of `ref` along its tangent;
// the points within `speculative` of the reference face. `flip`: the reference hull is the
// pair's second shape (the normal then points from `inc` to `ref`).
manifold clip_to_reference(const world_hull& ref, int i1, const world_hull& inc, int i2, bool flip, real speculative) {
    manifold m;
    const int i12 = next(ref, i1);
    const int i22 = next(inc, i2);
    const vec2 n = ref.n[i1];
    const vec2 v11 = ref.v[i1], v12 = ref.v[i12], v21 = inc.v[i2], v22 = inc.v[i22];
    const real radius = ref.radius + inc.radius;
    const vec2 tangent = (v12 - v11).normalized();
    clip_vertex v[2] = {{v21, feature_id(flip, false, i1, i2)}, {v22, feature_id(flip, false, i1, i22)}};
    if (!clip(v, tangent, tangent.dot(v11), feature_id(flip, true, i1, i2))) return m;
    if (!clip(v, vec2{-tangent}, -tangent.dot(v12), feature_id(flip, true, i12, i2))) return m;
    m.normal = flip ? vec2{-n} : n;
    for (const clip_vertex& c : v) {
        const real core = n.dot(c.x - v11);
        const real separation = core - radius;
        if (separation > speculative) continue;
        manifold_point& p = m.points[m.count++];
        p.separation = separation;
        p.point = c.x + n * (0.5f * (ref.radius - inc.radius - core));
        p.id = c.id;
    }
    return m;
}

}  // namespace

manifold collide_circles(const vec2& ca, real ra, const vec2& cb, real rb, real speculative) {
    manifold m;
    const vec2 d = cb - ca;
    const real dist = std::sqrt(d.squaredNorm());
    const real separation = dist - ra - rb;
    if (separation > speculative) return m;
    m.normal = dist > 0 ? vec2{d / dist} : vec2{1, 0};  // coincident centres: any fixed axis
    m.count = 1;
    m.points[0].separation = separation;
    m.points[0].point = ca + m.normal * (ra + 0.5f * separation);
    m.points[0].id = 0;
    return m;
}

manifold collide_hull_circle(const shape& a, const transform& xa, const vec2& centre, real radius, real speculative) {
    manifold m;
    const turned_shape turned = turn(a, xa.c, xa.s);
    const world_hull h = place(turned, xa.p);
    int edge = 0;
    real best = -3.4e38f;
    for (int i = 0; i < h.count; ++i) {
        const real s = h.n[i].dot(centre - h.v[i]);
        if (s > best) {
            best = s;
            edge = i;
        }
    }
    vec2 normal = h.n[edge];
    vec2 on_core = centre - normal * best;  // the centre projected on the edge's line
    real distance = best;
    if (best > 0) {
        // Outside the core: the closest point of the edge, which may be one of its vertices.
        const vec2 v1 = h.v[edge], e = h.v[next(h, edge)] - v1;
        const real u = std::clamp((centre - v1).dot(e) / e.squaredNorm(), real{0}, real{1});
        on_core = v1 + e * u;
        const vec2 d = centre - on_core;
        distance = std::sqrt(d.squaredNorm());
        if (distance > 0) normal = d / distance;
    }
    const real separation = distance - h.radius - radius;
    if (separation > speculative) return m;
    m.normal = normal;
    m.count = 1;
    m.points[0].separation = separation;
    m.points[0].point = on_core + normal * (h.radius + 0.5f * separation);
    m.points[0].id = static_cast<uint16_t>(edge);
    return m;
}

manifold collide_hulls(const shape& a, const transform& xa, const shape& b, const transform& xb, real speculative) {
    return collide_hulls(turn(a, xa.c, xa.s), xa.p, turn(b, xb.c, xb.s), xb.p, speculative);
}

manifold collide_hulls(const turned_shape& a, const vec2& pa, const turned_shape& b, const vec2& pb, real speculative) {
    manifold m;
    const world_hull ha = place(a, pa);
    const world_hull hb = place(b, pb);
    const real radius = ha.radius + hb.radius;
    int edge_a = 0, edge_b = 0;
    const real sep_a = max_separation(ha, hb, edge_a);
    if (sep_a > speculative + radius) return m;
    const real sep_b = max_separation(hb, ha, edge_b);
    if (sep_b > speculative + radius) return m;
    const bool flip = sep_b > sep_a + axis_tolerance;
    const world_hull& ref = flip ? hb : ha;
    const world_hull& inc = flip ? ha : hb;
    const int i1 = flip ? edge_b : edge_a;
    const int i12 = next(ref, i1);
    const vec2 n = ref.n[i1];
    const int i2 = incident_edge(inc, n);
    const int i22 = next(inc, i2);
    const vec2 v11 = ref.v[i1], v12 = ref.v[i12], v21 = inc.v[i2], v22 = inc.v[i22];
    const real core_separation = std::max(sep_a, sep_b);
    if (core_separation > -axis_tolerance) {
        // The cores are apart (or just touch): when their nearest features are two vertices,
        // the face normals underestimate the gap (two segments end to end on one line are 0
        // apart along every face normal) and the line between the vertices is the right
        // normal. Along the reference normal itself (boxes stacked exactly), the face is right.
        real s = 0, t = 0;
        closest_on_segments(v11, v12 - v11, v21, v22 - v21, s, t);
        const bool vertex_a = s == 0 || s == 1;
        const bool vertex_b = t == 0 || t == 1;
        const vec2 p1 = v11 + (v12 - v11) * s;
        const vec2 p2 = v21 + (v22 - v21) * t;
        const vec2 d = p2 - p1;
        const real distance = std::sqrt(d.squaredNorm());
        if (vertex_a && vertex_b && distance > 0.1f * axis_tolerance && d.dot(n) < 0.999f * distance) {
            const real separation = distance - radius;
            if (separation > speculative) return m;
            const vec2 normal = d / distance;  // from the reference hull to the incident one
            m.count = 1;
            m.normal = flip ? vec2{-normal} : normal;
            m.points[0].separation = separation;
            m.points[0].point = p1 + normal * (ref.radius + 0.5f * separation);
            m.points[0].id = feature_id(flip, false, s == 0 ? i1 : i12, t == 0 ? i2 : i22);
            return m;
        }
    }
    return clip_to_reference(ref, i1, inc, i2, flip, speculative);
}

manifold collide_on_edge(const shape& a, const transform& xa, const shape& b, const transform& xb, int edge,
                         real speculative) {
    const turned_shape ta = turn(a, xa.c, xa.s), tb = turn(b, xb.c, xb.s);
    const world_hull ha = place(ta, xa.p);
    const world_hull hb = place(tb, xb.p);
    return clip_to_reference(hb, edge, ha, incident_edge(ha, hb.n[edge]), true, speculative);
}

manifold collide(const shape& a, const transform& xa, const shape& b, const transform& xb, real speculative) {
    if (a.count == 1 && b.count == 1)
        return collide_circles(xa.apply(a.vertices[0]), a.radius, xb.apply(b.vertices[0]), b.radius, speculative);
    if (b.count == 1) return collide_hull_circle(a, xa, xb.apply(b.vertices[0]), b.radius, speculative);
    if (a.count == 1) {
        manifold m = collide_hull_circle(b, xb, xa.apply(a.vertices[0]), a.radius, speculative);
        m.normal = -m.normal;  // from a to b
        return m;
    }
    return collide_hulls(a, xa, b, xb, speculative);
}

manifold collide_wall(const shape& a, const transform& xa, const vec2& normal, real offset, real speculative) {
    manifold m;
    m.normal = normal;
    // The two deepest vertices within reach, the lower index first on ties.
    int first = -1, second = -1;
    real sep_first = 0, sep_second = 0;
    vec2 at_first{0, 0}, at_second{0, 0};
    for (int i = 0; i < a.count; ++i) {
        const vec2 w = xa.apply(a.vertices[i]);
        const real separation = offset - normal.dot(w) - a.radius;
        if (separation > speculative) continue;
        if (first < 0 || separation < sep_first) {
            second = first;
            sep_second = sep_first;
            at_second = at_first;
            first = i;
            sep_first = separation;
            at_first = w;
        } else if (second < 0 || separation < sep_second) {
            second = i;
            sep_second = separation;
            at_second = w;
        }
    }
    auto add = [&](int i, real separation, const vec2& w) {
        manifold_point& p = m.points[m.count++];
        p.separation = separation;
        p.point = w + normal * (a.radius + 0.5f * separation);
        p.id = static_cast<uint16_t>(i);
    };
    if (first >= 0) add(first, sep_first, at_first);
    if (second >= 0) add(second, sep_second, at_second);
    return m;
}

}  // namespace arena::world
