// Behaviours are deterministic for a (seed, bot index) and produce inputs the server accepts.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <vector>

#include "client_sim/behavior.hpp"
#include "server/world/presets.hpp"
#include "server/world/world.hpp"

namespace {

using arena::bots::behavior;
using arena::bots::behavior_kind;
using arena::protocol::BodyState;
namespace world = arena::world;

// Drives a lone body with a behaviour for `ticks`, with a second body that moves in a circle
// (something for seek to chase), and records the inputs.
std::vector<world::player_input> drive(behavior_kind kind, std::uint64_t seed, std::uint32_t index, int ticks,
                                       const std::string& preset = "asteroids") {
    world::world_config config = *world::preset_by_name(preset);
    config.rocks.count = 0;
    world::world w(config, 1);
    world::body b = world::make_body(config.player, config.size * 0.5f);
    const std::uint32_t id = *w.add_body(b);
    behavior bot(kind, seed, index, config);
    std::vector<world::player_input> out;
    for (int t = 0; t < ticks; ++t) {
        if (t % 3 == 0) {
            const world::body& own = *w.find(id);
            const float x = 50.0f + static_cast<float>(t % 200);
            const BodyState bodies[] = {
                BodyState(id, 1, own.position.x(), own.position.y(), 0, 0, own.angle, 0),
                BodyState(id + 1, 0, x, 60.0f, 0, 0, 0, 0),
            };
            bot.observe(bodies, id);
        }
        const world::player_input in = bot.next({w.find(id)});
        out.push_back(in);
        w.step({{world::body_id{id}, in}});
    }
    return out;
}

bool same_inputs(const std::vector<world::player_input>& a, const std::vector<world::player_input>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (std::memcmp(&a[i].thrust, &b[i].thrust, sizeof(float)) != 0 ||
            std::memcmp(&a[i].turn, &b[i].turn, sizeof(float)) != 0 || a[i].buttons != b[i].buttons)
            return false;
    }
    return true;
}

}  // namespace

TEST_CASE("a behaviour gives the same inputs for the same seed and index", "[bots][behavior]") {
    const auto kind = GENERATE(behavior_kind::random, behavior_kind::seek, behavior_kind::orbit, behavior_kind::idle);
    const auto preset = GENERATE(as<std::string>{}, "asteroids", "platformer");
    CHECK(same_inputs(drive(kind, 42, 7, 600, preset), drive(kind, 42, 7, 600, preset)));
}

TEST_CASE("seeds and bot indices give different random walks", "[bots][behavior]") {
    const auto base = drive(behavior_kind::random, 1, 0, 300);
    CHECK_FALSE(same_inputs(base, drive(behavior_kind::random, 2, 0, 300)));
    CHECK_FALSE(same_inputs(base, drive(behavior_kind::random, 1, 1, 300)));
}

TEST_CASE("inputs are finite and within [-1, 1], and idle sends zeros", "[bots][behavior]") {
    const auto kind = GENERATE(behavior_kind::random, behavior_kind::seek, behavior_kind::orbit);
    bool moved = false;
    for (const auto& in : drive(kind, 9, 2, 1200)) {
        REQUIRE(std::isfinite(in.thrust));
        REQUIRE(std::isfinite(in.turn));
        REQUIRE(std::abs(in.thrust) <= 1.0f);
        REQUIRE(std::abs(in.turn) <= 1.0f);
        REQUIRE((in.buttons & ~world::button_impulse) == 0);  // reserved bits stay 0
        moved = moved || in.thrust != 0.0f;
    }
    CHECK(moved);
    for (const auto& in : drive(behavior_kind::idle, 9, 2, 100)) {
        CHECK(in.thrust == 0.0f);
        CHECK(in.turn == 0.0f);
        CHECK(in.buttons == 0);
    }
}

TEST_CASE("mixed gives each bot index a kind, cycling through all five", "[bots][behavior]") {
    using arena::bots::behavior_choice;
    using arena::bots::resolve_behavior;
    CHECK(resolve_behavior(behavior_choice::mixed, 0) == behavior_kind::random);
    CHECK(resolve_behavior(behavior_choice::mixed, 1) == behavior_kind::seek);
    CHECK(resolve_behavior(behavior_choice::mixed, 2) == behavior_kind::orbit);
    CHECK(resolve_behavior(behavior_choice::mixed, 3) == behavior_kind::idle);
    CHECK(resolve_behavior(behavior_choice::mixed, 4) == behavior_kind::hunter);
    CHECK(resolve_behavior(behavior_choice::mixed, 5) == behavior_kind::random);
    CHECK(resolve_behavior(behavior_choice::hunter, 2) == behavior_kind::hunter);
    CHECK(resolve_behavior(behavior_choice::orbit, 1) == behavior_kind::orbit);
    CHECK(arena::bots::parse_behavior("seek") == behavior_choice::seek);
    CHECK_FALSE(arena::bots::parse_behavior("dance").has_value());
}

TEST_CASE("seek turns towards the body it chases", "[bots][behavior]") {
    world::world_config config = *world::preset_by_name("asteroids");
    world::body own = world::make_body(config.player, {100, 100});  // angle 0: facing +x
    own.id = 1;
    const float target_y = GENERATE(150.0f, 50.0f);
    behavior bot(behavior_kind::seek, 1, 0, config);
    const BodyState bodies[] = {BodyState(1, 1, 100, 100, 0, 0, 0, 0), BodyState(2, 0, 100, target_y, 0, 0, 0, 0)};
    bot.observe(bodies, 1);
    REQUIRE(bot.target_id() == 2);
    const world::player_input in = bot.next({&own});
    // Counter-clockwise (positive turn) towards +y, clockwise towards −y.
    if (target_y > 100)
        CHECK(in.turn > 0.5f);
    else
        CHECK(in.turn < -0.5f);
    CHECK(in.thrust == 0.0f);  // not facing it yet: turn first
}

TEST_CASE("orbit keeps a ship circling: it moves but stays within its circle's reach", "[bots][behavior]") {
    world::world_config config = *world::preset_by_name("asteroids");
    config.rocks.count = 0;
    world::world w(config, 1);
    const world::vec2 start = config.size * 0.5f;
    const std::uint32_t id = *w.add_body(world::make_body(config.player, start));
    behavior bot(behavior_kind::orbit, 5, 1, config);
    float travelled = 0;
    for (int t = 0; t < 60 * 30; ++t) {
        const world::vec2 before = w.find(id)->position;
        w.step({{world::body_id{id}, bot.next({w.find(id)})}});
        const world::vec2 d = world::displacement(before, w.find(id)->position, config);
        travelled += std::sqrt(d.squaredNorm());
    }
    // 30 s of steering: it went a long way (> 100 m) ...
    CHECK(travelled > 100.0f);
    // ... yet its average speed is bounded by the ship's top speed (about 26 m/s).
    CHECK(travelled / 30.0f < 30.0f);
}

TEST_CASE("hunter leads its prey, fires when lined up, ignores bullets and shies from close rocks",
          "[bots][behavior]") {
    world::world_config config = *world::preset_by_name("asteroids");
    world::body own = world::make_body(config.player, {100, 100});  // angle 0: facing +x, at rest
    own.id = 1;
    const auto react = [&](std::initializer_list<BodyState> others) {
        behavior bot(behavior_kind::hunter, 1, 0, config);
        std::vector<BodyState> bodies{BodyState(1, 1, 100, 100, 0, 0, 0, 0)};
        bodies.insert(bodies.end(), others);
        bot.observe(bodies, 1);
        return bot.next({&own});
    };
    constexpr std::uint8_t fire = 1u << 1;
    // Straight ahead, still, 40 m: lined up, so it thrusts and fires.
    const world::player_input ahead = react({BodyState(2, 0, 140, 100, 0, 0, 0, 0)});
    CHECK((ahead.buttons & fire) != 0);
    CHECK(ahead.thrust > 0.5f);
    // The same rock moving +y at 10 m/s: it aims ahead of it (counter-clockwise) and holds fire.
    const world::player_input leading = react({BodyState(2, 0, 140, 100, 0, 10, 0, 0)});
    CHECK(leading.turn > 0.1f);
    CHECK((leading.buttons & fire) == 0);
    // A bullet-fast body nearer than the rock is not prey.
    const world::player_input past_bullet =
        react({BodyState(2, 0, 104, 100, 40, 0, 0, 0), BodyState(3, 0, 140, 100, 0, 0, 0, 0)});
    CHECK((past_bullet.buttons & fire) != 0);
    // 6 m ahead: too close, it turns away (hard) and neither thrusts into it nor fires.
    const world::player_input close = react({BodyState(2, 0, 106, 100, 0, 0, 0, 0)});
    CHECK(std::abs(close.turn) == 1.0f);
    CHECK(close.thrust == 0.0f);
    CHECK((close.buttons & fire) == 0);
}
