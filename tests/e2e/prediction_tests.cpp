// The predictor against a local "server" world fed the same inputs: with no other body near
// ours, prediction is bit-exact whatever the latency; a server that deviates (a repeated input,
// a protocol slip) shows up as error or as a flagged problem. No shots are fired here, so a
// snapshot's tick (it places only the gun) is given as its ack.
#include <catch2/catch.hpp>
#include <cstring>
#include <deque>

#include "client_sim/behavior.hpp"
#include "client_sim/prediction.hpp"
#include "server/world/presets.hpp"
#include "server/world/world.hpp"

namespace {

using arena::bots::behavior;
using arena::bots::behavior_kind;
using arena::bots::predictor;
using arena::protocol::BodyState;
namespace world = arena::world;

constexpr std::uint32_t player = 2;

// The server's side: a world with the server's own config (not the predictor's local one)
// and our body at a known id, as the server would have spawned it.
struct server_world {
    world::world w;
    std::uint32_t id = 0;

    server_world(const world::world_config& config, std::uint64_t seed, world::vec2 at) : w(config, seed) {
        world::body b = world::make_body(config.player, at);
        b.owner = player;
        id = *w.add_body(b);
    }
    void step(const world::player_input& in) { w.step({{world::body_id{id}, in}}); }
    const world::body& own() const { return *w.find(id); }
    BodyState state() const {
        const world::body& b = own();
        return BodyState(b.id, b.owner, b.position.x(), b.position.y(), b.velocity.x(), b.velocity.y(), b.angle,
                         b.angular_velocity);
    }
};

bool same_bits(float a, float b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

// Every field the world's state holds for a body, bit for bit (impulse_cooldown included:
// it is not on the wire, the predictor must carry it itself).
bool same_body(const world::body& a, const world::body& b) {
    return same_bits(a.position.x(), b.position.x()) && same_bits(a.position.y(), b.position.y()) &&
           same_bits(a.velocity.x(), b.velocity.x()) && same_bits(a.velocity.y(), b.velocity.y()) &&
           same_bits(a.angle, b.angle) && same_bits(a.angular_velocity, b.angular_velocity) &&
           a.impulse_cooldown == b.impulse_cooldown;
}

world::world_config without_rocks(world::world_config c) {
    c.rocks.count = 0;
    return c;
}

}  // namespace

TEST_CASE("prediction is bit-exact with zero latency and no other bodies", "[bots][prediction]") {
    const auto preset = GENERATE(as<std::string>{}, "asteroids", "platformer");
    const world::world_config config = without_rocks(*world::preset_by_name(preset));
    server_world server(config, 1, config.size * 0.5f);
    predictor p(config, server.id, player);
    behavior drive(behavior_kind::random, 7, 0, config);  // thrust, turn and impulses

    const BodyState first = server.state();
    REQUIRE(p.on_snapshot(0, 0, &first).own_found);
    for (std::uint32_t s = 1; s <= 600; ++s) {
        const world::player_input in = drive.next({p.body()});
        p.on_input(s, in);
        server.step(in);
        REQUIRE(same_body(*p.body(), server.own()));  // before the snapshot: pure prediction
        const BodyState now = server.state();
        const predictor::correction c = p.on_snapshot(s, s, &now);
        REQUIRE(c.error.has_value());
        REQUIRE(*c.error == 0.0f);
        REQUIRE(c.replayed == 0);
        REQUIRE(p.unacknowledged() == 0);
    }
}

TEST_CASE("prediction stays bit-exact with latency: snapshots every 3 ticks, delivered late", "[bots][prediction]") {
    const auto preset = GENERATE(as<std::string>{}, "asteroids", "platformer");
    const std::uint32_t delay = GENERATE(0u, 1u, 4u, 9u);  // ticks between a snapshot and its arrival
    const world::world_config config = without_rocks(*world::preset_by_name(preset));
    server_world server(config, 1, {config.size.x() * 0.3f, config.size.y() * 0.2f});
    predictor p(config, server.id, player);
    behavior drive(behavior_kind::random, 11, 3, config);

    struct in_flight {
        std::uint32_t arrives;
        std::uint32_t ack;
        BodyState state;
    };
    std::deque<in_flight> wire;
    wire.push_back({0, 0, server.state()});
    std::uint32_t measured = 0;
    for (std::uint32_t t = 0; t <= 900; ++t) {
        // The snapshots due now arrive first, as a client's reader would see them.
        while (!wire.empty() && wire.front().arrives <= t) {
            const predictor::correction c = p.on_snapshot(wire.front().ack, wire.front().ack, &wire.front().state);
            REQUIRE(c.problem == predictor::ack_problem::none);
            if (c.error) {
                REQUIRE(*c.error == 0.0f);
                ++measured;
            }
            wire.pop_front();
            // Reset and replay land exactly where the server is now.
            if (p.body() != nullptr && t > 0) REQUIRE(same_body(*p.body(), server.own()));
        }
        const std::uint32_t s = t + 1;
        const world::player_input in = drive.next({p.body()});
        p.on_input(s, in);
        server.step(in);
        if (s % 3 == 0) wire.push_back({s + delay, s, server.state()});
    }
    CHECK(measured > 250);
}

TEST_CASE("with other bodies in the server's world, prediction is exact until one touches ours", "[bots][prediction]") {
    // The full asteroids preset: 40 drifting rocks the predictor does not simulate.
    const world::world_config config = *world::preset_by_name("asteroids");
    server_world server(config, 5, {200, 200});
    predictor p(config, server.id, player);
    behavior drive(behavior_kind::random, 3, 1, config);
    const BodyState first = server.state();
    p.on_snapshot(0, 0, &first);
    bool touched = false;
    std::uint32_t exact = 0;
    for (std::uint32_t s = 1; s <= 1200 && !touched; ++s) {
        const world::player_input in = drive.next({p.body()});
        p.on_input(s, in);
        server.step(in);
        const auto bodies = server.w.bodies();
        for (const auto& c : server.w.last_contacts()) {
            if (bodies[c.a].id == server.id || (c.with == world::wall::none && bodies[c.b].id == server.id))
                touched = true;
        }
        if (touched) break;
        const BodyState now = server.state();
        const predictor::correction c = p.on_snapshot(s, s, &now);
        REQUIRE(*c.error == 0.0f);
        ++exact;
    }
    CHECK(exact > 10);
}

TEST_CASE("a repeated input on the server shows as error once, then prediction is exact again", "[bots][prediction]") {
    const world::world_config config = without_rocks(*world::preset_by_name("asteroids"));
    server_world server(config, 1, {100, 100});
    predictor p(config, server.id, player);
    const BodyState first = server.state();
    p.on_snapshot(0, 0, &first);
    const world::player_input full{1.0f, 0.2f, 0};
    std::uint32_t s = 0;
    auto tick = [&](bool underrun) {
        if (!underrun) p.on_input(++s, full);
        server.step(full);  // on an underrun the server repeats the last input, ack unchanged
    };
    for (int i = 0; i < 60; ++i) tick(false);
    const BodyState before = server.state();
    REQUIRE(*p.on_snapshot(s, s, &before).error == 0.0f);

    // The server's tick comes before our next input: it repeats input s, then consumes s+1.
    tick(true);
    tick(false);
    const BodyState slipped = server.state();
    const predictor::correction late = p.on_snapshot(s, s, &slipped);
    REQUIRE(late.error.has_value());
    CHECK(*late.error > 0.0f);
    // One tick of motion at most: the body is the same, only one Δt further along.
    CHECK(*late.error < 30.0f * config.dt * 2);

    // Corrected: the next predictions start from the server's state.
    for (int i = 0; i < 3; ++i) tick(false);
    const BodyState after = server.state();
    REQUIRE(*p.on_snapshot(s, s, &after).error == 0.0f);
}

TEST_CASE("acknowledgements that go back or run ahead are flagged and ignored", "[bots][prediction]") {
    const world::world_config config = without_rocks(*world::preset_by_name("asteroids"));
    server_world server(config, 1, {100, 100});
    predictor p(config, server.id, player);
    const BodyState state = server.state();
    p.on_snapshot(0, 0, &state);
    for (std::uint32_t s = 1; s <= 5; ++s) p.on_input(s, {});
    CHECK(p.on_snapshot(6, 6, &state).problem == predictor::ack_problem::ahead);
    CHECK(p.on_snapshot(4, 4, &state).problem == predictor::ack_problem::none);
    CHECK(p.unacknowledged() == 1);
    CHECK(p.on_snapshot(3, 3, &state).problem == predictor::ack_problem::went_back);
}

TEST_CASE("a snapshot without our body keeps every input for the next one", "[bots][prediction]") {
    const world::world_config config = without_rocks(*world::preset_by_name("asteroids"));
    predictor p(config, 9, player);
    for (std::uint32_t s = 1; s <= 3; ++s) p.on_input(s, {1.0f, 0.0f, 0});
    const predictor::correction c = p.on_snapshot(2, 2, nullptr);
    CHECK_FALSE(c.own_found);
    CHECK(p.unacknowledged() == 3);
    CHECK(p.body() == nullptr);
}

TEST_CASE("the local world drops the server's rocks and keeps everything else", "[bots][prediction]") {
    const world::world_config server = *world::preset_by_name("asteroids");
    const world::world_config local = predictor::local_config(server);
    CHECK(local.rocks.count == 0);
    CHECK(local.dt == server.dt);
    CHECK(local.size == server.size);
    CHECK(local.boundary == server.boundary);
    CHECK(local.control.thrust_force == server.control.thrust_force);
    CHECK(local.player.mass == server.player.mass);
}
