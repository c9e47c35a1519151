// What an interpolating bot shows of the others (client_sim/shown_view.hpp): a fixed delay
// behind its present, between the two snapshots around that moment (a body new in the newer
// shown from it on), carried on by velocity past the newest; the shortest way across a
// wrapping world's edge.
#include <algorithm>
#include <catch2/catch.hpp>
#include <vector>

#include "client_sim/shown_view.hpp"
#include "server/world/presets.hpp"

using namespace arena;
using bots::shown_view;

namespace {

protocol::BodyState at(uint32_t id, float x, float y, float vx = 0, float vy = 0) {
    return {id, 0, x, y, vx, vy, 0, 0};
}

world::vec2 position_of(const std::vector<shown_view::shown_body>& bodies, uint32_t id) {
    for (const auto& b : bodies)
        if (b.id == id) return b.position;
    FAIL("body " << id << " not shown");
    return {0, 0};
}

}  // namespace

TEST_CASE("the delay is the largest lag of the last second plus a snapshot interval", "[bots][view]") {
    shown_view v(3);
    CHECK(v.moment(100) == 0);  // nothing shown before a snapshot
    const std::vector<protocol::BodyState> none;
    v.on_snapshot(100, 104, none);  // 4 ticks behind the present when it came
    CHECK(v.delay() == (4 + 3) * 256);
    v.on_snapshot(103, 109, none);  // 6 behind
    v.on_snapshot(106, 108, none);  // 2 behind: the largest of the second stays
    CHECK(v.delay() == (6 + 3) * 256);
    CHECK(v.moment(120) == (120 - 9) * 256);
    for (uint32_t t = 109; t < 109 + 3 * 25; t += 3) v.on_snapshot(t, t + 2, none);  // a second later
    CHECK(v.delay() == (2 + 3) * 256);
}

TEST_CASE("a body is shown between the snapshots around the moment, or carried on past the newest", "[bots][view]") {
    world::world_config config = world::asteroids_preset();
    shown_view v(3);
    v.on_snapshot(100, 102, std::vector<protocol::BodyState>{at(5, 10, 20, 60, 0)});
    v.on_snapshot(103, 105, std::vector<protocol::BodyState>{at(5, 13, 20, 60, 0), at(6, 50, 50, 0, 6)});
    // A third of the way from tick 100 to 103.
    const auto between = v.at(101 * 256, config);
    CHECK(position_of(between, 5).x() == Approx(11.0f));
    // Body 6 is only in the newer snapshot: it came between the two, and is not shown before it.
    CHECK(std::none_of(between.begin(), between.end(), [](const shown_view::shown_body& b) { return b.id == 6; }));
    CHECK(position_of(v.at(103 * 256, config), 6).y() == Approx(50.0f));
    // Past the newest: on by velocity (60 m/s for half a tick).
    const auto ahead = v.at(103 * 256 + 128, config);
    CHECK(position_of(ahead, 5).x() == Approx(13.0f + 60.0f * 0.5f / 60.0f));
}

TEST_CASE("between two snapshots across a wrapping world's edge, the short way round", "[bots][view]") {
    world::world_config config = world::asteroids_preset();
    REQUIRE(config.boundary == world::boundary::wrap);
    const float edge = config.size.x();
    shown_view v(3);
    v.on_snapshot(100, 102, std::vector<protocol::BodyState>{at(5, edge - 1.0f, 20)});
    v.on_snapshot(103, 105, std::vector<protocol::BodyState>{at(5, 1.0f, 20)});
    const world::vec2 halfway = position_of(v.at(101 * 256 + 128, config), 5);
    // 1 m short of the edge, then 1 m past it: halfway is at the edge, not in the middle.
    CHECK((halfway.x() == Approx(edge) || halfway.x() == Approx(0.0f).margin(1e-3)));
}

TEST_CASE("a body that went or came between two snapshots is shown while the server says it was there",
          "[bots][view]") {
    world::world_config config = world::asteroids_preset();
    shown_view v(3);
    v.on_snapshot(100, 102, std::vector<protocol::BodyState>{at(7, 10, 10, 60, 0)});
    v.on_snapshot(103, 105, std::vector<protocol::BodyState>{at(8, 30, 30, 0, 60), at(9, 40, 40)});
    v.went(7, 102);  // rock 7 was hit: the state of tick 102 first lacks it; 8 came as it went
    const auto has = [](const std::vector<shown_view::shown_body>& bodies, uint32_t id) {
        return std::any_of(bodies.begin(), bodies.end(), [&](const shown_view::shown_body& b) { return b.id == id; });
    };
    const auto before = v.at(101 * 256, config);
    REQUIRE(has(before, 7));
    CHECK(position_of(before, 7).x() == Approx(11.0f));  // carried on from tick 100
    CHECK_FALSE(has(before, 8));
    const auto after = v.at(102 * 256, config);
    CHECK_FALSE(has(after, 7));
    REQUIRE(has(after, 8));
    CHECK(position_of(after, 8).y() == Approx(29.0f));  // carried back from tick 103
    // Body 9 also came, but the respawn event says when: tick 103.
    v.came(9, 103);
    CHECK_FALSE(has(v.at(102 * 256, config), 9));
}
