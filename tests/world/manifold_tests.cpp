// The narrow phase against hand-computed cases: points, normal and separation for each pair of
// kinds, face against face (two points), vertex against face (one), vertex against vertex, and
// the same scene turned a quarter turn.
#include <catch2/catch.hpp>

#include "server/world/manifold.hpp"
#include "server/world/shape.hpp"

using namespace arena::world;

namespace {

constexpr real spec = 0.02f;

transform at(real x, real y, real c = 1, real s = 0) {
    return {{x, y}, c, s};
}

void check_point(const manifold& m, int k, real x, real y, real separation) {
    INFO("point " << k);
    CHECK(m.points[k].point.x() == Approx(x).margin(1e-5));
    CHECK(m.points[k].point.y() == Approx(y).margin(1e-5));
    CHECK(m.points[k].separation == Approx(separation).margin(1e-5));
}

// The point of m with the smaller x (or y), so that checks do not depend on clip order.
int lower(const manifold& m, bool along_x = true) {
    const real a = along_x ? m.points[0].point.x() : m.points[0].point.y();
    const real b = along_x ? m.points[1].point.x() : m.points[1].point.y();
    return a <= b ? 0 : 1;
}

}  // namespace

TEST_CASE("box on box, face to face: two points at the overlap's ends", "[world][manifold]") {
    const manifold m = collide(make_box(0.5f, 0.5f), at(0, 0), make_box(0.5f, 0.5f), at(0.2f, 0.95f), spec);
    REQUIRE(m.count == 2);
    CHECK(m.normal.x() == Approx(0).margin(1e-6));
    CHECK(m.normal.y() == Approx(1));
    const int lo = lower(m);
    check_point(m, lo, -0.3f, 0.475f, -0.05f);
    check_point(m, 1 - lo, 0.5f, 0.475f, -0.05f);
    CHECK(m.points[0].id != m.points[1].id);
}

TEST_CASE("box on box turned a quarter turn gives the turned manifold", "[world][manifold]") {
    // The scene above, turned by +90°: (x, y) → (−y, x).
    const manifold m =
        collide(make_box(0.5f, 0.5f), at(0, 0, 0, 1), make_box(0.5f, 0.5f), at(-0.95f, 0.2f, 0, 1), spec);
    REQUIRE(m.count == 2);
    CHECK(m.normal.x() == Approx(-1));
    CHECK(m.normal.y() == Approx(0).margin(1e-6));
    const int lo = lower(m, false);
    check_point(m, lo, -0.475f, -0.3f, -0.05f);
    check_point(m, 1 - lo, -0.475f, 0.5f, -0.05f);
}

TEST_CASE("a box standing on its corner: one point, vertex against face", "[world][manifold]") {
    const real h = 0.70710678f;  // cos 45° = sin 45°
    // B's lowest corner 0.05 below A's top face.
    const manifold m = collide(make_box(0.5f, 0.5f), at(0, 0), make_box(0.5f, 0.5f), at(0, 0.45f + h, h, h), spec);
    REQUIRE(m.count == 1);
    CHECK(m.normal.y() == Approx(1));
    check_point(m, 0, 0, 0.475f, -0.05f);
}

TEST_CASE("two boxes corner to corner, apart: the normal joins the corners", "[world][manifold]") {
    // B's lower-left corner 0.01 m up and right of A's upper-right corner.
    const real d = 0.01f * 0.70710678f;
    const manifold m = collide(make_box(0.5f, 0.5f), at(0, 0), make_box(0.5f, 0.5f), at(1 + d, 1 + d), spec);
    REQUIRE(m.count == 1);
    CHECK(m.normal.x() == Approx(0.70710678f));
    CHECK(m.normal.y() == Approx(0.70710678f));
    CHECK(m.points[0].separation == Approx(0.01f).margin(1e-5));
}

TEST_CASE("boxes farther apart than the speculative distance have no manifold", "[world][manifold]") {
    CHECK(collide(make_box(0.5f, 0.5f), at(0, 0), make_box(0.5f, 0.5f), at(0, 1.03f), spec).count == 0);
    CHECK(collide(make_box(0.5f, 0.5f), at(0, 0), make_box(0.5f, 0.5f), at(0, 1.015f), spec).count == 2);
}

TEST_CASE("circle on a box's face and at its corner", "[world][manifold]") {
    manifold m = collide(make_box(0.5f, 0.5f), at(0, 0), make_circle(0.5f), at(0.1f, 0.9f), spec);
    REQUIRE(m.count == 1);
    CHECK(m.normal.y() == Approx(1));
    check_point(m, 0, 0.1f, 0.45f, -0.1f);
    // At the corner: the normal points from the corner to the centre.
    m = collide(make_box(0.5f, 0.5f), at(0, 0), make_circle(0.5f), at(0.8f, 0.8f), spec);
    REQUIRE(m.count == 1);
    CHECK(m.normal.x() == Approx(0.70710678f));
    CHECK(m.normal.y() == Approx(0.70710678f));
    CHECK(m.points[0].separation == Approx(0.3f * 1.41421356f - 0.5f).margin(1e-5));
    // The circle first: the same contact, normal reversed.
    const manifold r = collide(make_circle(0.5f), at(0.8f, 0.8f), make_box(0.5f, 0.5f), at(0, 0), spec);
    REQUIRE(r.count == 1);
    CHECK(r.normal.x() == Approx(-0.70710678f));
    CHECK(r.points[0].separation == Approx(m.points[0].separation));
}

TEST_CASE("circle on circle", "[world][manifold]") {
    const manifold m = collide(make_circle(1), at(0, 0), make_circle(0.5f), at(1.4f, 0), spec);
    REQUIRE(m.count == 1);
    CHECK(m.normal.x() == Approx(1));
    check_point(m, 0, 0.95f, 0, -0.1f);
}

TEST_CASE("capsule lying on a box: two points where the box's top ends", "[world][manifold]") {
    const manifold m = collide(make_box(0.5f, 0.5f), at(0, 0), make_capsule(1.0f, 0.25f), at(0, 0.73f), spec);
    REQUIRE(m.count == 2);
    CHECK(m.normal.y() == Approx(1));
    const int lo = lower(m);
    check_point(m, lo, -0.5f, 0.49f, -0.02f);
    check_point(m, 1 - lo, 0.5f, 0.49f, -0.02f);
}

TEST_CASE("capsule standing on a box: one point under its lower end", "[world][manifold]") {
    // Axis along y (a quarter turn), lower end's cap 0.01 into the box.
    const manifold m = collide(make_box(1, 0.5f), at(0, 0), make_capsule(0.5f, 0.2f), at(0.3f, 1.19f, 0, 1), spec);
    REQUIRE(m.count == 1);
    CHECK(m.normal.y() == Approx(1));
    check_point(m, 0, 0.3f, 0.495f, -0.01f);
}

TEST_CASE("segment against circle, box and capsule", "[world][manifold]") {
    const shape ground = make_segment({-2, 0}, {2, 0});
    manifold m = collide(ground, at(0, 0), make_circle(0.5f), at(1, 0.4f), spec);
    REQUIRE(m.count == 1);
    CHECK(m.normal.y() == Approx(1));
    check_point(m, 0, 1, -0.05f, -0.1f);
    m = collide(ground, at(0, 0), make_box(0.5f, 0.5f), at(0, 0.48f), spec);
    REQUIRE(m.count == 2);
    CHECK(m.normal.y() == Approx(1));
    const int lo = lower(m);
    check_point(m, lo, -0.5f, -0.01f, -0.02f);
    check_point(m, 1 - lo, 0.5f, -0.01f, -0.02f);
    // The segment's underside: a box below it is pushed down.
    m = collide(ground, at(0, 0), make_box(0.5f, 0.5f), at(1, -0.49f), spec);
    REQUIRE(m.count == 2);
    CHECK(m.normal.y() == Approx(-1));
    CHECK(m.points[0].separation == Approx(-0.01f).margin(1e-5));
    // A capsule beyond the segment's end, touching its end vertex with its cap.
    m = collide(ground, at(0, 0), make_capsule(0.5f, 0.25f), at(2.74f, 0.0f), spec);
    REQUIRE(m.count == 1);
    CHECK(m.normal.x() == Approx(1));
    CHECK(m.points[0].separation == Approx(-0.01f).margin(1e-5));
}

TEST_CASE("a box against a wall: its two deepest corners", "[world][manifold]") {
    // Floor: the wall is {y ≤ 0}, i.e. {(0, −1)·x ≥ 0}.
    const manifold m = collide_wall(make_box(0.5f, 0.5f), at(3, 0.49f), {0, -1}, 0, spec);
    REQUIRE(m.count == 2);
    const int lo = lower(m);
    check_point(m, lo, 2.5f, -0.005f, -0.01f);
    check_point(m, 1 - lo, 3.5f, -0.005f, -0.01f);
}

TEST_CASE("feature ids stay the same while the same features touch", "[world][manifold]") {
    const manifold a = collide(make_box(0.5f, 0.5f), at(0, 0), make_box(0.5f, 0.5f), at(0.2f, 0.95f), spec);
    const manifold b = collide(make_box(0.5f, 0.5f), at(0, 0), make_box(0.5f, 0.5f), at(0.25f, 0.96f), spec);
    REQUIRE(a.count == 2);
    REQUIRE(b.count == 2);
    CHECK(a.points[lower(a)].id == b.points[lower(b)].id);
    CHECK(a.points[1 - lower(a)].id == b.points[1 - lower(b)].id);
}
