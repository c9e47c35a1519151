// Static bodies in a world that wraps: a platform across the seam holds a body up on both sides
// of it, a body near the seam meets a wall on the other side, and the static index's pairs are
// those of a brute-force search over every image of every static body.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <set>
#include <tuple>
#include <vector>

#include "server/world/integrate.hpp"
#include "server/world/rng.hpp"
#include "server/world/static_index.hpp"
#include "server/world/trig.hpp"
#include "server/world/world.hpp"

using namespace arena::world;

namespace {

world_config wrap_world(vec2 gravity) {
    world_config c;
    c.boundary = boundary::wrap;
    c.size = {40, 40};
    c.gravity = gravity;
    c.air_density = 0;
    return c;
}

body_material slippery() {
    body_material m;
    m.friction = 0;
    m.restitution = 0;
    return m;
}

// A 1 m box at rest on the platform's top (y = 10) at x = 37, sliding right at 2 m/s: it
// crosses the seam at x = 40 after 1.5 s and goes on from x = 0.
void slide_across_the_seam(world& w) {
    body b = make_body(slippery(), make_box(0.5f, 0.5f), {37, 10.5f});
    b.velocity = {2, 0};
    const uint32_t id = *w.add_body(b, make_box(0.5f, 0.5f));
    real lowest = 11, highest = 0;
    for (int k = 0; k < 180; ++k) {
        w.step({});
        const body& now = *w.find(id);
        lowest = std::min(lowest, now.position.y());
        highest = std::max(highest, now.position.y());
    }
    const body& end = *w.find(id);
    CHECK(end.position.x() == Approx(3).margin(0.01));  // 37 + 2·3 − 40
    CHECK(end.velocity.x() == Approx(2).margin(0.01));
    CHECK(lowest > 10.49f);
    CHECK(highest < 10.505f);
}

// The box of a static body where it lies (its position as given, not wrapped).
aabb box_of(const body& b, std::span<const shape> pool) {
    const shape s = b.shape == no_shape ? make_circle(b.radius) : pool[b.shape];
    const cos_sin turn = compute_cos_sin(b.angle);
    return compute_aabb(s, b.position, turn.c, turn.s);
}

// Does `fixed`, moved by any whole number of world sizes, overlap `box`?
bool meets_any_image(const aabb& fixed, const aabb& box, const vec2& size) {
    for (int i = -2; i <= 2; ++i)
        for (int j = -2; j <= 2; ++j)
            if (overlaps(moved(fixed, vec2{static_cast<real>(i) * size.x(), static_cast<real>(j) * size.y()}), box))
                return true;
    return false;
}

}  // namespace

TEST_CASE("a box slides across the seam on a static segment that crosses it", "[world][wrap]") {
    // From x = 30 to x = 50 at y = 10: its body sits at x = 40, the seam, and wraps to 0.
    world w(wrap_world({0, -9.81f}), 0);
    body_material ground = slippery();
    ground.density = 0;
    const shape segment = make_segment({-10, 0}, {10, 0});
    REQUIRE(w.add_body(make_body(ground, segment, {40, 10}), segment));
    slide_across_the_seam(w);
}

TEST_CASE("a box slides across the seam on a chain that crosses it", "[world][wrap]") {
    // 2 m segments from x = 30 to x = 50: some sit beyond the seam and wrap.
    world w(wrap_world({0, -9.81f}), 0);
    std::vector<vec2> points;
    for (int k = 0; k <= 10; ++k) points.push_back({30 + 2 * static_cast<real>(k), 10});
    REQUIRE(w.add_chain(points, slippery()));
    slide_across_the_seam(w);
}

TEST_CASE("a box slides with a = −μ·g along a chain that goes round the world", "[world][wrap][chain]") {
    // 20 segments of 2 m from x = 0 to x = 40, the first point one world width before the last:
    // the chain's ends are neighbours across the seam, so the box crosses it as any other joint.
    world w(wrap_world({0, -9.81f}), 0);
    std::vector<vec2> points;
    for (int k = 0; k <= 20; ++k) points.push_back({2 * static_cast<real>(k), 10});
    body_material ground = slippery();
    ground.friction = 0.2f;
    const auto ids = w.add_chain(points, ground);
    REQUIRE(ids);
    CHECK(w.shape_of(*w.find(ids->front())).chain.has_prev);
    CHECK(w.shape_of(*w.find(ids->back())).chain.has_next);
    // Launched at 3 m/s from x = 38.5: it slows at μ·g = 1.962 m/s² and crosses the seam at
    // about 0.63 s and stops after 1.53 s, 2.29 m on, at x ≈ 0.79.
    body b = make_body(ground, make_box(0.5f, 0.5f), {38.5f, 10.5f});
    b.velocity = {3, 0};
    const uint32_t id = *w.add_body(b, make_box(0.5f, 0.5f));
    std::vector<real> vx;
    real lowest = 11, highest = 0, spin = 0;
    for (int k = 0; k < 100; ++k) {
        w.step({});
        const body& now = *w.find(id);
        vx.push_back(now.velocity.x());
        lowest = std::min(lowest, now.position.y());
        highest = std::max(highest, now.position.y());
        spin = std::max(spin, std::abs(now.angular_velocity));
    }
    CHECK((vx[75] - vx[5]) / (70.0f / 60.0f) == Approx(-0.2 * 9.81).epsilon(0.01));
    CHECK(w.find(id)->position.x() == Approx(0.79f).margin(0.05));
    CHECK(lowest > 10.49f);
    CHECK(highest < 10.505f);
    CHECK(spin < 0.02f);
}

TEST_CASE("a ball near the seam bounces off a wall on the other side of it", "[world][wrap]") {
    // A static wall 1 m thick at x in [0, 1]: a ball going right from x = 36 meets its left
    // face at x = 40 (that is 0) and bounces back; one going left from x = 4 meets its right face.
    world w(wrap_world({0, 0}), 0);
    body_material wall = slippery();
    wall.density = 0;
    const shape slab = make_box(0.5f, 10);
    REQUIRE(w.add_body(make_body(wall, slab, {0.5f, 20}), slab));
    body_material ball = slippery();
    ball.radius = 0.5f;
    ball.restitution = 1;
    body right = make_body(ball, {36, 20});
    right.velocity = {5, 0};
    body left = make_body(ball, {4, 20});
    left.velocity = {-5, 0};
    const uint32_t from_left = *w.add_body(right);
    const uint32_t from_right = *w.add_body(left);
    real rightmost = 0, leftmost = 40;
    for (int k = 0; k < 120; ++k) {
        w.step({});
        rightmost = std::max(rightmost, w.find(from_left)->position.x());
        leftmost = std::min(leftmost, w.find(from_right)->position.x());
    }
    CHECK(rightmost < 39.51f);  // it never crossed the seam into the wall
    CHECK(leftmost > 1.49f);
    CHECK(w.find(from_left)->velocity.x() == Approx(-5).margin(0.01));
    CHECK(w.find(from_right)->velocity.x() == Approx(5).margin(0.01));
}

TEST_CASE("the static index's pairs in a wrapping world are a brute-force search's over every image",
          "[world][wrap][broadphase]") {
    const world_config config = wrap_world({0, 0});
    rng r(42);
    // Static segments and boxes anywhere, many across a seam (positions also beyond the world,
    // as a config may give them), and query boxes all over the world.
    std::vector<body> bodies;
    std::vector<shape> pool;
    body_material fixed;
    fixed.density = 0;
    for (int i = 0; i < 200; ++i) {
        const real x = r.uniform(-5, 45);
        const real y = r.uniform(-5, 45);
        const real half = r.uniform(0.2f, 6);
        const real tilt = r.uniform(-1, 1);
        const shape s = i % 2 == 0 ? make_segment({-half, -tilt}, {half, tilt}) : make_box(half, 0.5f);
        body b = make_body(fixed, s, {x, y});
        b.angle = r.uniform(-3, 3);
        b.shape = static_cast<uint32_t>(pool.size());
        pool.push_back(s);
        bodies.push_back(b);
    }
    static_index index;
    index.build(bodies, pool, config);
    REQUIRE(index.entries().size() == bodies.size());
    std::vector<uint32_t> scratch;
    size_t across = 0, pairs = 0;
    for (int q = 0; q < 2000; ++q) {
        const real x = r.uniform(0, 40);
        const real y = r.uniform(0, 40);
        const real hx = r.uniform(0.1f, 2);
        const real hy = r.uniform(0.1f, 2);
        const aabb box{{x - hx, y - hy}, {x + hx, y + hy}};
        std::vector<uint32_t> found;
        index.query(box, scratch, [&](const static_index::entry& e, const vec2& offset) {
            found.push_back(e.index);
            CHECK(overlaps(moved(e.box, offset), box));
            if (offset != vec2{0, 0}) ++across;
        });
        std::vector<uint32_t> expected;
        for (uint32_t i = 0; i < bodies.size(); ++i)
            if (meets_any_image(box_of(bodies[i], pool), box, config.size)) expected.push_back(i);
        INFO("query " << q);
        REQUIRE(found == expected);  // the same pairs, in index order, each once
        pairs += found.size();
    }
    CHECK(pairs > 2000);  // the search found something
    CHECK(across > 200);  // and many of it across a seam
}

TEST_CASE("a wrapping world's contacts with static bodies are a brute force's over every image", "[world][wrap]") {
    // Circles and boxes at rest, without gravity, near static segments and boxes that sit at or
    // across the seams: one step's contacts with static bodies are exactly the pairs whose
    // narrow phase finds a contact at some image of the static body.
    const world_config config = wrap_world({0, 0});
    world w(config, 0);
    rng r(7);
    body_material fixed;
    fixed.density = 0;
    for (int i = 0; i < 40; ++i) {
        // Near a seam: within 3 m of x = 0 or of y = 0 (either side, as given).
        const bool near_x = i % 2 == 0;
        const real x = near_x ? r.uniform(-3, 3) : r.uniform(0, 40);
        const real y = near_x ? r.uniform(0, 40) : r.uniform(-3, 3);
        const real half = r.uniform(0.5f, 3);
        const shape s = i % 3 == 0 ? make_box(half, 0.3f) : make_segment({-half, 0}, {half, 0});
        body b = make_body(fixed, s, {x < 0 ? x + 40 : x, y});
        b.angle = r.uniform(-3, 3);
        w.add_body(b, s);
    }
    body_material m;
    for (int i = 0; i < 300; ++i) {
        const real x = r.uniform(0, 40);
        const real y = r.uniform(0, 40);
        const shape s = i % 2 == 0 ? make_circle(r.uniform(0.2f, 1)) : make_box(r.uniform(0.2f, 1), r.uniform(0.2f, 1));
        body b = make_body(m, s, {x, y});
        b.angle = r.uniform(-3, 3);
        w.add_body(b, s);
    }
    const std::vector<body> before(w.bodies().begin(), w.bodies().end());
    w.step({});
    std::set<std::pair<uint32_t, uint32_t>> found;
    for (const contact& c : w.last_contacts())
        if (before[c.b].is_static() && c.with == wall::none) found.insert({c.a, c.b});
    std::set<std::pair<uint32_t, uint32_t>> expected;
    for (uint32_t i = 0; i < before.size(); ++i) {
        if (before[i].is_static()) continue;
        const shape own = w.shape_of(before[i]);
        const cos_sin turn_a = compute_cos_sin(before[i].angle);
        const transform xa{before[i].position, turn_a.c, turn_a.s};
        for (uint32_t k = 0; k < before.size(); ++k) {
            if (!before[k].is_static()) continue;
            const shape other = w.shape_of(before[k]);
            const cos_sin turn_b = compute_cos_sin(before[k].angle);
            body wrapped = before[k];
            wrap_position(wrapped, config);
            for (int dx = -1; dx <= 1; ++dx)
                for (int dy = -1; dy <= 1; ++dy) {
                    const vec2 at =
                        wrapped.position + vec2{static_cast<real>(dx) * 40.0f, static_cast<real>(dy) * 40.0f};
                    const transform xb{at, turn_b.c, turn_b.s};
                    if (collide(own, xa, other, xb, config.speculative_distance).count > 0) expected.insert({i, k});
                }
        }
    }
    CHECK(expected.size() > 20);
    size_t across = 0;
    for (const auto& [a, b] : expected)
        if (std::abs(before[a].position.x() - before[b].position.x()) > 20 ||
            std::abs(before[a].position.y() - before[b].position.y()) > 20)
            ++across;
    CHECK(across > 3);
    CHECK(found == expected);
}
