// The session with the server (client_sim/session.hpp), which the bots and the browser SDK's
// WebAssembly module both run: after a respawn of its own player the session predicts the new
// ship, it paces its inputs, and it places the own bullets where the prediction has them.
#include <catch2/catch.hpp>
#include <vector>

#include "client_sim/session.hpp"
#include "games/asteroids/asteroids_shot.hpp"
#include "protocol/config_hash.hpp"
#include "protocol/decode.hpp"
#include "protocol/delta/codec.hpp"
#include "protocol/snapshot.hpp"
#include "protocol/verify.hpp"
#include "server/config/config_json.hpp"
#include "server/world/presets.hpp"
#include "server/world/world.hpp"

using namespace arena;

namespace {

constexpr std::uint32_t own_player = 3;
constexpr std::uint32_t first_ship = 7;

// `asteroids_rules`: played by the Asteroids rules, so that the session predicts own shots.
protocol::frame_bytes welcome(bool asteroids_rules = false) {
    world::world_config config = *world::preset_by_name("asteroids");
    if (asteroids_rules) config.rules = "asteroids";
    protocol::welcome_info w;
    w.player_id = own_player;
    w.entity_id = first_ship;
    w.tick = 100;
    w.tick_rate = 60;
    w.snapshot_rate = 20;
    w.preset = "asteroids";
    w.world_config = config::config_to_json(config);
    w.world_config_hash = protocol::world_config_hash(w.world_config);
    w.world_version = world::world_version;
    return protocol::encode_welcome(w);
}

protocol::game_event respawn(std::uint32_t sequence, std::uint32_t player, std::uint32_t body) {
    protocol::game_event e;
    e.sequence = sequence;
    e.kind = protocol::GameEventKind::respawn;
    e.player = player;
    e.body = body;
    return e;
}

// A full snapshot of `bodies` (by increasing id) with `events`, acknowledging input `ack`.
std::vector<std::uint8_t> snapshot(std::uint32_t tick, std::uint32_t ack, std::vector<protocol::BodyState> bodies,
                                   std::vector<protocol::game_event> events = {}) {
    flatbuffers::FlatBufferBuilder fbb;
    protocol::game_list game;
    game.events = std::move(events);
    const auto frame = protocol::encode_snapshot(fbb, tick, ack, bodies, nullptr, game.empty() ? nullptr : &game);
    return {frame.begin(), frame.end()};
}

protocol::BodyState ship(std::uint32_t id, std::uint32_t owner, float x) {
    return protocol::BodyState(id, owner, x, 20.0f, 0.0f, 0.0f, 0.0f, 0.0f);
}

// A delta snapshot of the own ship alone, encoded in full (no baseline), acknowledging input
// `ack`, that says `extra_waiting` inputs wait beyond the first.
std::vector<std::uint8_t> delta_snapshot(std::uint32_t tick, std::uint32_t ack, std::uint16_t extra_waiting) {
    const std::vector<protocol::delta::quantized_body> view{
        protocol::delta::quantize(ship(first_ship, own_player, 10.0f))};
    const std::vector<std::uint8_t> bytes = protocol::delta::encode(view, std::nullopt, {0, 60});
    flatbuffers::FlatBufferBuilder fbb;
    const auto frame = protocol::encode_delta_snapshot(fbb, tick, ack, 0, bytes, nullptr, nullptr, extra_waiting);
    return {frame.begin(), frame.end()};
}

// The sequence an Input frame carries.
std::uint32_t sequence_of(std::span<const std::uint8_t> frame) {
    const auto verified = protocol::verify_message(frame, protocol::client_frame_limits);
    REQUIRE(verified);
    const protocol::Input* input = verified.value->payload_as_Input();
    REQUIRE(input != nullptr);
    return input->sequence();
}

}  // namespace

TEST_CASE("after its own respawn the session predicts the new ship, and other players' respawns change nothing",
          "[client]") {
    bots::session s({.delta_snapshots = false});
    (void)s.hello("probe", "");
    REQUIRE(s.feed(welcome()) == protocol::Payload::Welcome);
    (void)s.input(0, 0, 0);
    REQUIRE(s.feed(snapshot(103, 1, {ship(first_ship, own_player, 10.0f)})) == protocol::Payload::Snapshot);
    REQUIRE(s.predicted() != nullptr);
    CHECK(s.predicted()->position.x() == Approx(10.0f).margin(0.5));

    // The first ship is gone; another player respawns: still no own body to predict from.
    (void)s.input(0, 0, 0);
    REQUIRE(s.feed(snapshot(106, 2, {ship(13, 4, 80.0f)}, {respawn(1, 4, 13)})) == protocol::Payload::Snapshot);
    CHECK(s.entity_id() == first_ship);

    // Our respawn: body 12 is ours from this snapshot on, and the prediction starts from it.
    (void)s.input(0, 0, 0);
    REQUIRE(s.feed(snapshot(109, 3, {ship(12, own_player, 50.0f), ship(13, 4, 80.0f)},
                            {respawn(1, 4, 13), respawn(2, own_player, 12)})) == protocol::Payload::Snapshot);
    CHECK(s.entity_id() == 12);
    (void)s.input(0, 0, 0);
    REQUIRE(s.predicted() != nullptr);
    CHECK(s.predicted()->position.x() == Approx(50.0f).margin(0.5));

    // The same events again (resent until acknowledged) are taken once: nothing changes.
    REQUIRE(s.feed(snapshot(112, 4, {ship(12, own_player, 51.0f), ship(13, 4, 80.0f)},
                            {respawn(1, 4, 13), respawn(2, own_player, 12)})) == protocol::Payload::Snapshot);
    CHECK(s.entity_id() == 12);
    CHECK(s.error().empty());
}

TEST_CASE("after two delta snapshots in a row with extra inputs waiting the session leaves one tick's input out",
          "[client][pacing]") {
    bots::session s;
    (void)s.hello("probe", "");
    REQUIRE(s.feed(welcome()) == protocol::Payload::Welcome);
    std::uint32_t tick = 101;
    std::uint32_t sent = 0;  // the newest sequence an Input carried
    const auto send = [&]() {
        const auto frame = s.input(1.0f, 0.0f, 0);
        if (frame.empty()) return false;
        CHECK(sequence_of(frame) == sent + 1);  // consecutive, across a left-out tick too
        sent = sequence_of(frame);
        return true;
    };
    for (int i = 0; i < 3; ++i) REQUIRE(send());

    // None waiting beyond the first, for many snapshots: every tick's input is sent.
    for (int i = 0; i < 10; ++i) {
        REQUIRE(s.feed(delta_snapshot(tick += 3, sent - 1, 0)) == protocol::Payload::Snapshot);
        for (int t = 0; t < 3; ++t) REQUIRE(send());
    }
    CHECK(s.inputs_left_out() == 0);

    // One snapshot with extra waiting may be a burst: nothing is left out yet.
    REQUIRE(s.feed(delta_snapshot(tick += 3, sent - 1, 2)) == protocol::Payload::Snapshot);
    for (int t = 0; t < 3; ++t) REQUIRE(send());
    CHECK(s.inputs_left_out() == 0);

    // The second in a row: the next tick's input is left out, neither sent nor predicted.
    REQUIRE(s.feed(delta_snapshot(tick += 3, sent - 1, 1)) == protocol::Payload::Snapshot);
    REQUIRE(s.predicted() != nullptr);
    const auto before = s.predicted()->position;
    CHECK_FALSE(send());
    CHECK(s.out().empty());
    CHECK(s.inputs_left_out() == 1);
    CHECK(s.last_sequence() == sent);
    CHECK(s.predicted()->position == before);
    // The ticks after it are sent again, carrying the next sequences.
    for (int t = 0; t < 3; ++t) REQUIRE(send());
    CHECK((s.predicted()->position - before).norm() > 0.0f);

    // A snapshot acknowledging an input from before the gap still shows the old queue: it
    // does not count towards the next leaving out.
    for (int i = 0; i < 2; ++i) REQUIRE(s.feed(delta_snapshot(tick += 3, sent - 3, 1)) == protocol::Payload::Snapshot);
    CHECK(send());
    CHECK(s.inputs_left_out() == 1);
    CHECK(s.error().empty());
}

TEST_CASE("an own shot is placed at the nose as it is fired and once the server's bullet where the prediction had it",
          "[client][shots]") {
    bots::session s({.delta_snapshots = false});
    (void)s.hello("probe", "");
    REQUIRE(s.feed(welcome(true)) == protocol::Payload::Welcome);
    (void)s.input(0, 0, 0);
    REQUIRE(s.feed(snapshot(103, 1, {ship(first_ship, own_player, 10.0f)})) == protocol::Payload::Snapshot);
    CHECK(s.own_bullets().empty());

    // Input 2 fires from the ship at rest, facing +x: the bullet spawns 1.5 + 0.2 + 0.1 m ahead
    // at 2 N·s / 0.05 kg = 40 m/s, and is drawn after that input's step.
    (void)s.input(0, 0, rules::button_fire);
    std::vector<bots::own_bullet> bullets = s.own_bullets();
    REQUIRE(bullets.size() == 1);
    CHECK(bullets[0].body_id == 0);
    CHECK(bullets[0].sequence == 2);
    const float dt = 1.0f / 60.0f;
    CHECK(bullets[0].x == Approx(11.8f + 40.0f * dt).margin(1e-4));
    CHECK(bullets[0].y == Approx(20.0f).margin(1e-4));
    CHECK(bullets[0].vx == Approx(40.0f).margin(1e-4));
    (void)s.input(0, 0, 0);
    (void)s.input(0, 0, 0);
    bullets = s.own_bullets();
    REQUIRE(bullets.size() == 1);
    const bots::own_bullet before = bullets[0];
    CHECK(before.x == Approx(11.8f + 3 * 40.0f * dt).margin(1e-4));

    // The server's snapshot after input 3 holds the bullet (body 20), moved by the world's two
    // steps since its spawn, with its origin: the session now places that body, one step on,
    // where it had the predicted one (the same float steps: bit for bit).
    const float spawn_x = 10.0f + (1.5f + 0.2f + 0.1f);
    float x = spawn_x;
    for (int k = 0; k < 2; ++k) x += before.vx * dt;
    protocol::shape_list described;
    protocol::shape_desc round;
    round.id = 20;
    round.kind = 3;
    round.radius = 0.2f;
    described.append(round);
    described.origins.emplace_back(20, own_player, 2, spawn_x, 20.0f, before.vx, before.vy);
    flatbuffers::FlatBufferBuilder fbb;
    const std::vector<protocol::BodyState> view{ship(first_ship, own_player, 10.0f),
                                                protocol::BodyState(20, 0, x, 20.0f, before.vx, before.vy, 0, 0)};
    const auto frame = protocol::encode_snapshot(fbb, 106, 3, view, &described);
    REQUIRE(s.feed({frame.begin(), frame.end()}) == protocol::Payload::Snapshot);
    bullets = s.own_bullets();
    REQUIRE(bullets.size() == 1);
    CHECK(bullets[0].body_id == 20);
    CHECK(bullets[0].sequence == 2);
    CHECK(bullets[0].x == before.x);
    CHECK(bullets[0].y == before.y);

    // Gone from the view (it hit something): no longer drawn.
    REQUIRE(s.feed(snapshot(109, 4, {ship(first_ship, own_player, 10.0f)})) == protocol::Payload::Snapshot);
    CHECK(s.own_bullets().empty());
    CHECK(s.error().empty());
}
