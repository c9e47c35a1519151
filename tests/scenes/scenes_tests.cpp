// The shared scenes and scripted inputs: inside their bounds, and the same for the same seed
// (the replay golden file, the benchmarks and the bots rely on it).
#include <catch2/catch.hpp>
#include <cmath>

#include "scenes/scatter.hpp"
#include "scenes/sticks.hpp"

using namespace arena;

TEST_CASE("scattered circles lie in their box with radii in range, the same for a seed", "[scenes]") {
    const scenes::scatter_box box{{-5, 10}, {60, 40}, 0.2f, 2.0f};
    world::body_material m;
    m.friction = 0.25f;
    world::rng a(3), b(3);
    for (int i = 0; i < 2000; ++i) {
        const world::body p = scenes::scattered_circle(a, box, m);
        const world::body q = scenes::scattered_circle(b, box, m);
        REQUIRE(p.position == q.position);
        REQUIRE(p.radius == q.radius);
        CHECK(p.radius >= 0.2f);
        CHECK(p.radius < 2.0f);
        CHECK(p.position.x() >= -5);
        CHECK(p.position.x() < 60);
        CHECK(p.position.y() >= 10);
        CHECK(p.position.y() < 40);
        CHECK(p.velocity == world::vec2{0, 0});
        CHECK(p.friction == 0.25f);
    }
}

TEST_CASE("a human's stick moves about one tick in 20 and keeps within [-1, 1]", "[scenes]") {
    world::rng r(11);
    world::player_input stick{0, 0, world::button_impulse};
    int moves = 0;
    const int ticks = 20000;
    for (int k = 0; k < ticks; ++k) {
        const world::player_input before = stick;
        const bool moved = scenes::move_stick_now_and_then(r, stick);
        moves += moved;
        if (!moved) CHECK((stick.thrust == before.thrust && stick.turn == before.turn));
        CHECK(std::abs(stick.thrust) <= 1);
        CHECK(std::abs(stick.turn) <= 1);
        CHECK(stick.buttons == world::button_impulse);  // left alone
    }
    CHECK(moves > ticks / 20 / 2);
    CHECK(moves < ticks / 20 * 2);
}

TEST_CASE("a wandering stick takes small steps within its bounds and sometimes fires", "[scenes]") {
    world::rng r(5), again(5);
    scenes::wandering_stick s, t;
    world::player_input last{};
    int impulses = 0;
    for (int k = 0; k < 9000; ++k) {
        const world::player_input in = s.next(r);
        const world::player_input same = t.next(again);
        REQUIRE((in.thrust == same.thrust && in.turn == same.turn && in.buttons == same.buttons));
        CHECK(in.thrust >= -0.2f);
        CHECK(in.thrust <= 1.0f);
        CHECK(std::abs(in.turn) <= 1.0f);
        CHECK(std::abs(in.thrust - last.thrust) <= 0.1f + 1e-6f);
        CHECK(std::abs(in.turn - last.turn) <= 0.2f + 1e-6f);
        impulses += in.buttons == world::button_impulse;
        last = in;
    }
    CHECK(impulses > 9000 / 90 / 2);
    CHECK(impulses < 9000 / 90 * 2);
}
