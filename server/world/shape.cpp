#include "server/world/shape.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "server/world/trig.hpp"

namespace arena::world {

namespace {

real cross(const vec2& a, const vec2& b) {
    return a.x() * b.y() - a.y() * b.x();
}

// The outward normal of the edge a → b of a counter-clockwise hull: the edge turned clockwise.
vec2 edge_normal(const vec2& a, const vec2& b) {
    const vec2 e = b - a;
    const real length = std::sqrt(e.squaredNorm());
    return vec2{e.y() / length, -e.x() / length};
}

void set_normals(shape& s) {
    for (int i = 0; i < s.count; ++i) {
        const int j = i + 1 < s.count ? i + 1 : 0;
        s.normals[i] = edge_normal(s.vertices[i], s.vertices[j]);
    }
}

}  // namespace

shape make_circle(real radius) {
    shape s;
    s.kind = shape_kind::circle;
    s.count = 1;
    s.radius = radius;
    return s;
}

shape make_capsule(real half_length, real radius) {
    shape s;
    s.kind = shape_kind::capsule;
    s.count = 2;
    s.radius = radius;
    s.vertices[0] = {-half_length, 0};
    s.vertices[1] = {half_length, 0};
    set_normals(s);
    return s;
}

shape make_box(real hx, real hy, real radius) {
    shape s;
    s.kind = shape_kind::polygon;
    s.count = 4;
    s.radius = radius;
    s.vertices[0] = {-hx, -hy};
    s.vertices[1] = {hx, -hy};
    s.vertices[2] = {hx, hy};
    s.vertices[3] = {-hx, hy};
    s.normals[0] = {0, -1};
    s.normals[1] = {1, 0};
    s.normals[2] = {0, 1};
    s.normals[3] = {-1, 0};
    return s;
}

shape make_segment(const vec2& a, const vec2& b) {
    shape s;
    s.kind = shape_kind::segment;
    s.count = 2;
    s.radius = 0;
    s.vertices[0] = a;
    s.vertices[1] = b;
    set_normals(s);
    return s;
}

result<centred_shape> make_polygon(std::span<const vec2> points, real radius) {
    using made = result<centred_shape>;
    if (points.size() > static_cast<size_t>(max_polygon_vertices))
        return made::failure("a polygon has at most 8 vertices, got " + std::to_string(points.size()));
    // Gift wrapping from the lowest-leftmost point: at most 8 points, so O(n²) is nothing, and
    // ties (collinear points) resolve to the farthest point, so the hull has no flat vertices.
    std::vector<vec2> p(points.begin(), points.end());
    if (p.size() < 3) return made::failure("a polygon needs at least 3 vertices, got " + std::to_string(p.size()));
    size_t start = 0;
    for (size_t i = 1; i < p.size(); ++i) {
        if (p[i].x() < p[start].x() || (p[i].x() == p[start].x() && p[i].y() < p[start].y())) start = i;
    }
    std::vector<vec2> hull;
    size_t current = start;
    for (size_t guard = 0; guard <= p.size(); ++guard) {
        hull.push_back(p[current]);
        size_t next = current == 0 ? 1 : 0;
        for (size_t i = 0; i < p.size(); ++i) {
            if (i == current) continue;
            const real turn = cross(p[next] - p[current], p[i] - p[current]);
            const bool farther = (p[i] - p[current]).squaredNorm() > (p[next] - p[current]).squaredNorm();
            if (turn < 0 || (turn == 0 && farther)) next = i;
        }
        current = next;
        if (current == start) break;
    }
    real area2 = 0;
    for (size_t i = 0; i < hull.size(); ++i) area2 += cross(hull[i], hull[(i + 1) % hull.size()]);
    const real linear_slop = 0.005f;
    if (hull.size() < 3 || area2 <= linear_slop * linear_slop)
        return made::failure("the polygon's vertices have no area (collinear or repeated)");
    shape s;
    s.kind = shape_kind::polygon;
    s.count = static_cast<uint8_t>(hull.size());
    s.radius = radius;
    for (size_t i = 0; i < hull.size(); ++i) s.vertices[i] = hull[i];
    const mass_properties m = compute_mass(s, 1);
    for (size_t i = 0; i < hull.size(); ++i) s.vertices[i] -= m.centre;
    set_normals(s);
    return made::success({s, m.centre});
}

mass_properties compute_mass(const shape& s, real density) {
    mass_properties out;
    const real r = s.radius;
    if (s.count == 1) {
        // A disc: I = ½·m·r².
        out.mass = density * pi * r * r;
        out.centre = s.vertices[0];
        out.inertia = 0.5f * out.mass * r * r;
        return out;
    }
    if (s.count == 2) {
        // A rectangle of length L and width 2r, and two half discs at its ends. A half disc's
        // centroid lies 4r/(3π) beyond the end, so about the capsule's centre its inertia is
        // m_half·(½r² + (L/2)² + 2·(L/2)·4r/(3π)) (parallel axis from the half disc's centroid).
        const vec2 a = s.vertices[0], b = s.vertices[1];
        const real length = std::sqrt((b - a).squaredNorm());
        const real box_mass = density * 2 * r * length;
        const real disc_mass = density * pi * r * r;
        const real h = 0.5f * length;
        const real lc = 4 * r / (3 * pi);
        out.mass = box_mass + disc_mass;
        out.centre = (a + b) * 0.5f;
        out.inertia = box_mass * (4 * r * r + length * length) / 12 + disc_mass * (0.5f * r * r + h * h + 2 * h * lc);
        return out;
    }
    // A polygon: triangles fanned from its first vertex (exact), computed about that vertex
    // for precision, then moved to the centroid.
    const vec2 origin = s.vertices[0];
    real area = 0;
    vec2 centre{0, 0};
    real inertia_origin = 0;  // per unit density, about `origin`
    for (int i = 1; i + 1 < s.count; ++i) {
        const vec2 e1 = s.vertices[i] - origin;
        const vec2 e2 = s.vertices[i + 1] - origin;
        const real d = cross(e1, e2);
        const real tri = 0.5f * d;
        area += tri;
        centre += (e1 + e2) * (tri / 3);
        // ∫(x² + y²) over the triangle (0, e1, e2) = d/12 · (|e1|² + e1·e2 + |e2|²).
        inertia_origin += (d / 12) * (e1.squaredNorm() + e1.dot(e2) + e2.squaredNorm());
    }
    centre /= area;
    real mass = density * area;
    real inertia = density * inertia_origin;
    vec2 moment = centre * mass;  // first moment about `origin`
    if (r > 0) {
        // Edge strips r wide, outside each edge, and a disc's worth of corner sectors.
        for (int i = 0; i < s.count; ++i) {
            const int j = i + 1 < s.count ? i + 1 : 0;
            const vec2 a = s.vertices[i] - origin, b = s.vertices[j] - origin;
            const real length = std::sqrt((b - a).squaredNorm());
            const real m = density * length * r;
            const vec2 c = (a + b) * 0.5f + s.normals[i] * (0.5f * r);
            mass += m;
            moment += c * m;
            inertia += m * (length * length + r * r) / 12 + m * c.squaredNorm();
            // The corner sector at vertex i, between the normals of edges i − 1 and i. Its first
            // moment about the vertex is exact without an angle: ∫∫ ρ·ρ'·(cos θ, sin θ) ρ' dρ' dθ
            // = ρ·r³/3 · (sin θ₂ − sin θ₁, cos θ₁ − cos θ₂), and those are the normals'
            // components. Its mass is a share of the disc's, exact when the corners are equal
            // (boxes, regular polygons).
            const vec2 n1 = s.normals[i > 0 ? i - 1 : s.count - 1], n2 = s.normals[i];
            const real corner = density * pi * r * r / static_cast<real>(s.count);
            const vec2 first = vec2{n2.y() - n1.y(), n1.x() - n2.x()} * (density * r * r * r / 3);
            mass += corner;
            moment += a * corner + first;
            inertia += 0.5f * corner * r * r + corner * a.squaredNorm() + 2 * a.dot(first);
        }
    }
    const vec2 c = moment / mass;
    out.mass = mass;
    out.centre = origin + c;
    out.inertia = inertia - mass * c.squaredNorm();  // parallel axis back to the centre of mass
    return out;
}

real bounding_radius(const shape& s) {
    real far = 0;
    for (int i = 0; i < s.count; ++i) far = std::max(far, s.vertices[i].squaredNorm());
    return std::sqrt(far) + s.radius;
}

aabb compute_aabb(const shape& sh, const vec2& position, real c, real s) {
    return compute_aabb(turn(sh, c, s), position);
}

turned_shape turn(const shape& sh, real c, real s) {
    turned_shape t;
    t.count = sh.count;
    t.radius = sh.radius;
    for (int i = 0; i < sh.count; ++i) {
        const vec2& v = sh.vertices[i];
        const vec2& n = sh.normals[i];
        t.vertices[i] = {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
        t.normals[i] = {c * n.x() - s * n.y(), s * n.x() + c * n.y()};
    }
    return t;
}

aabb compute_aabb(const turned_shape& sh, const vec2& position) {
    aabb box;
    for (int i = 0; i < sh.count; ++i) {
        const vec2 w = sh.vertices[i] + position;
        if (i == 0) {
            box.lo = box.hi = w;
        } else {
            box.lo = box.lo.cwiseMin(w);
            box.hi = box.hi.cwiseMax(w);
        }
    }
    const vec2 r{sh.radius, sh.radius};
    box.lo -= r;
    box.hi += r;
    return box;
}

}  // namespace arena::world
