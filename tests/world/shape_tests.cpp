// Shapes: mass, centre of mass and inertia against their closed forms (and, for the shapes
// whose formula we derived ourselves, against a brute-force integration over a fine grid).
#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <vector>

#include "server/world/manifold.hpp"
#include "server/world/shape.hpp"

using namespace arena::world;

namespace {

// Mass, centroid and inertia of the set of points within `radius` of the shape's core, summed
// over an n×n grid of cells covering its box.
mass_properties integrate(const shape& s, int n) {
    const aabb box = compute_aabb(s, {0, 0}, 1, 0);
    const double w = box.hi.x() - box.lo.x(), h = box.hi.y() - box.lo.y();
    const double cell = (w / n) * (h / n);
    double m = 0, mx = 0, my = 0, i0 = 0;
    for (int iy = 0; iy < n; ++iy)
        for (int ix = 0; ix < n; ++ix) {
            const double x = box.lo.x() + (ix + 0.5) * w / n, y = box.lo.y() + (iy + 0.5) * h / n;
            // Inside: within `radius` of the core (a tiny circle as a probe).
            const manifold probe = collide_hull_circle(s, {}, vec2{static_cast<real>(x), static_cast<real>(y)}, 0, 0);
            if (s.count >= 2 && probe.count == 0) continue;
            if (s.count == 1 && x * x + y * y > s.radius * s.radius) continue;
            m += cell;
            mx += cell * x;
            my += cell * y;
            i0 += cell * (x * x + y * y);
        }
    mass_properties out;
    out.mass = static_cast<real>(m);
    out.centre = {static_cast<real>(mx / m), static_cast<real>(my / m)};
    out.inertia = static_cast<real>(i0 - m * (mx / m * mx / m + my / m * my / m));
    return out;
}

}  // namespace

TEST_CASE("a box's mass and inertia are m = ρ·w·h and I = m·(w² + h²)/12", "[world][shape]") {
    const mass_properties m = compute_mass(make_box(1.0f, 0.5f), 2.0f);
    CHECK(m.mass == Approx(4.0));
    CHECK(m.centre.norm() == Approx(0).margin(1e-6));
    CHECK(m.inertia == Approx(4.0 * (4.0 + 1.0) / 12.0));
}

TEST_CASE("a right triangle's centroid is at a third of its legs and I = m·(a² + b²)/18", "[world][shape]") {
    const std::vector<vec2> points{{0, 0}, {2, 0}, {0, 2}};
    const auto r = make_polygon(points);
    REQUIRE(r.ok());
    CHECK(r.value.centre.x() == Approx(2.0 / 3));
    CHECK(r.value.centre.y() == Approx(2.0 / 3));
    const mass_properties m = compute_mass(r.value.geometry, 1.0f);
    CHECK(m.mass == Approx(2.0));
    CHECK(m.centre.norm() == Approx(0).margin(1e-6));  // make_polygon moved it to the origin
    CHECK(m.inertia == Approx(2.0 * (4.0 + 4.0) / 18.0));
}

TEST_CASE("make_polygon takes the convex hull, counter-clockwise, and refuses degenerate input", "[world][shape]") {
    // A square given clockwise, with an interior point and a point on an edge.
    const std::vector<vec2> points{{0, 0}, {0, 2}, {1, 1}, {2, 2}, {2, 0}, {1, 0}};
    const auto r = make_polygon(points);
    REQUIRE(r.ok());
    CHECK(r.value.geometry.count == 4);
    real area2 = 0;
    for (int i = 0; i < 4; ++i) {
        const vec2 a = r.value.geometry.vertices[i], b = r.value.geometry.vertices[(i + 1) % 4];
        area2 += a.x() * b.y() - a.y() * b.x();
    }
    CHECK(area2 == Approx(8.0));  // positive: counter-clockwise
    const std::vector<vec2> line{{0, 0}, {1, 1}, {2, 2}};
    CHECK_FALSE(make_polygon(line).ok());
    CHECK(make_polygon(line).error.find("no area") != std::string::npos);
    const std::vector<vec2> nine(9, vec2{0, 0});
    CHECK(make_polygon(nine).error.find("at most 8") != std::string::npos);
}

TEST_CASE("a capsule's and a rounded box's mass and inertia match a fine integration", "[world][shape]") {
    for (const shape& s : {make_capsule(1.0f, 0.4f), make_box(0.6f, 0.3f, 0.1f), make_circle(0.7f)}) {
        const mass_properties exact = compute_mass(s, 1.0f);
        const mass_properties grid = integrate(s, 1500);
        INFO("kind " << static_cast<int>(s.kind));
        CHECK(exact.mass == Approx(grid.mass).epsilon(0.002));
        CHECK(exact.inertia == Approx(grid.inertia).epsilon(0.005));
    }
}

TEST_CASE("a bounding box follows the rotation", "[world][shape]") {
    // A 2×1 box turned a quarter turn is 1×2.
    const aabb box = compute_aabb(make_box(1.0f, 0.5f), {3, 4}, 0, 1);
    CHECK(box.lo.x() == Approx(2.5));
    CHECK(box.hi.x() == Approx(3.5));
    CHECK(box.lo.y() == Approx(3.0));
    CHECK(box.hi.y() == Approx(5.0));
}

TEST_CASE("a turned shape placed at its body is the shape turned and placed in one go, bit for bit", "[world][shape]") {
    // The broadphase turns each body's shape once a step and the narrow phase adds the positions
    // per pair: the results must be the bits transform::apply and compute_aabb give, or replays
    // would differ.
    const std::vector<vec2> corners{{0.1f, -0.3f}, {1.7f, 0.2f}, {-0.4f, 0.9f}};
    const auto triangle = make_polygon(corners);
    REQUIRE(triangle);
    const shape shapes[] = {make_box(0.5f, 0.5f), make_box(1.3f, 0.27f, 0.05f), triangle.value.geometry,
                            make_capsule(0.8f, 0.3f), make_segment({-1.1f, 0.2f}, {0.7f, -0.4f})};
    const auto bits = [](real x) {
        return std::bit_cast<uint32_t>(x);
    };
    for (const shape& sh : shapes) {
        for (int k = 0; k < 64; ++k) {
            const real angle = 0.37f * static_cast<real>(k) - 11.0f;
            const real c = std::cos(angle), s = std::sin(angle);
            const vec2 position{-37.1f + 1.93f * static_cast<real>(k), 5.3f + 0.61f * static_cast<real>(k)};
            const transform x{position, c, s};
            const turned_shape t = turn(sh, c, s);
            REQUIRE(t.count == sh.count);
            CHECK(bits(t.radius) == bits(sh.radius));
            for (int i = 0; i < sh.count; ++i) {
                const vec2 placed = t.vertices[i] + position;
                const vec2 expected = x.apply(sh.vertices[i]);
                const vec2 normal = x.rotate(sh.normals[i]);
                CHECK(bits(placed.x()) == bits(expected.x()));
                CHECK(bits(placed.y()) == bits(expected.y()));
                CHECK(bits(t.normals[i].x()) == bits(normal.x()));
                CHECK(bits(t.normals[i].y()) == bits(normal.y()));
            }
            // The box: the placed vertices' extremes, grown by the rounding.
            vec2 lo = x.apply(sh.vertices[0]), hi = lo;
            for (int i = 1; i < sh.count; ++i) {
                lo = lo.cwiseMin(x.apply(sh.vertices[i]));
                hi = hi.cwiseMax(x.apply(sh.vertices[i]));
            }
            const aabb box = compute_aabb(sh, position, c, s);
            CHECK(bits(box.lo.x()) == bits(lo.x() - sh.radius));
            CHECK(bits(box.lo.y()) == bits(lo.y() - sh.radius));
            CHECK(bits(box.hi.x()) == bits(hi.x() + sh.radius));
            CHECK(bits(box.hi.y()) == bits(hi.y() + sh.radius));
        }
    }
}
