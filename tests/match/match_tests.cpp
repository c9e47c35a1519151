// The match without sockets: connections are recorders of what they were sent.
#include <catch2/catch.hpp>
#include <limits>
#include <memory>
#include <stdexcept>

#include "match/drive.hpp"
#include "protocol/decode.hpp"
#include "protocol/verify.hpp"
#include "server/match/match.hpp"
#include "server/world/presets.hpp"

using namespace arena;
using namespace arena::match_test;

namespace {

struct fake_client : match::connection {
    std::vector<protocol::frame_bytes> frames;
    std::vector<uint32_t> snapshot_acks;
    std::vector<uint32_t> snapshot_ticks;
    std::optional<protocol::RejectCode> rejected;
    std::string reason;
    void send(protocol::frame_bytes frame) override { frames.push_back(std::move(frame)); }
    void send_snapshot(const protocol::snapshot_encoder& s, uint32_t ack) override {
        send_snapshot_frame(s.frame_with_ack(ack));
    }
    void send_snapshot_frame(std::span<const uint8_t> bytes) override {
        protocol::frame_bytes frame;
        const protocol::snapshot_view snap = read_snapshot(bytes, frame);
        snapshot_acks.push_back(snap.ack_sequence);
        snapshot_ticks.push_back(snap.tick);
    }
    void close(protocol::RejectCode code, std::string_view why) override {
        rejected = code;
        reason = why;
    }
    std::string bye;
    void close_with_bye(std::string_view reason) override { bye = reason; }
    std::string_view peer() const override { return "test"; }
};

match::match_config make_config(uint32_t max_players = 64, uint32_t max_inputs_per_second = 0) {
    match::match_config c;
    c.tick_rate = 60;
    c.snapshot_rate = 20;
    c.admission.max_players = max_players;
    c.admission.max_inputs_per_second = max_inputs_per_second;
    return c;
}

protocol::hello_msg hello(uint16_t version = protocol::protocol_version) {
    return {version, "tester", ""};
}

}  // namespace

TEST_CASE("a joined player gets a Welcome with its body after the next tick", "[match]") {
    match::match g(make_config(2), world::asteroids_preset());
    fake_client c;
    const uint32_t joined = join(g, c, hello());
    REQUIRE(joined != 0);
    CHECK(c.frames.empty());
    g.tick();
    REQUIRE(c.frames.size() == 1);
    auto m = protocol::verify_message(c.frames[0], protocol::server_frame_limits);
    REQUIRE(m);
    auto welcome = protocol::decode_welcome(*m.value);
    REQUIRE(welcome);
    CHECK(welcome.value.player_id == joined);
    const world::body* b = g.state().find(welcome.value.entity_id);
    REQUIRE(b);
    CHECK(b->owner == welcome.value.player_id);
    CHECK(welcome.value.world_config == g.world_config_json());
}

TEST_CASE("version mismatch and a full server are refused with their codes", "[match]") {
    match::match g(make_config(1), world::asteroids_preset());
    fake_client a, b, c;
    REQUIRE(join(g, a, hello(99)) == 0);
    REQUIRE(a.rejected);
    CHECK(*a.rejected == protocol::RejectCode::version_mismatch);
    REQUIRE(join(g, b, hello()) != 0);
    REQUIRE(join(g, c, hello()) == 0);
    REQUIRE(c.rejected);
    CHECK(*c.rejected == protocol::RejectCode::server_full);
}

TEST_CASE("snapshots go out every tick_rate/snapshot_rate ticks with the last consumed sequence", "[match]") {
    match::match g(make_config(), world::asteroids_preset());
    fake_client c;
    REQUIRE(join(g, c, hello()) != 0);
    g.tick();  // spawns
    for (uint32_t s = 1; s <= 12; ++s) {
        REQUIRE(send_input(g, c, {s, 1, 0, 0}));
        g.tick();
    }
    REQUIRE(c.snapshot_ticks.size() == 4);  // ticks 3, 6, 9, 12 of 13
    for (size_t i = 1; i < c.snapshot_ticks.size(); ++i) CHECK(c.snapshot_ticks[i] == c.snapshot_ticks[i - 1] + 3);
    // Tick k (1-based after the spawn tick) consumed input k.
    CHECK(c.snapshot_acks.back() == c.snapshot_ticks.back() - 1);
}

TEST_CASE("a NaN input and an input flood are refused", "[match]") {
    match::match g(make_config(64, 10), world::asteroids_preset());
    fake_client c;
    REQUIRE(join(g, c, hello()) != 0);
    g.tick();
    REQUIRE_FALSE(send_input(g, c, {1, std::numeric_limits<float>::quiet_NaN(), 0, 0}));
    REQUIRE(c.rejected);
    CHECK(*c.rejected == protocol::RejectCode::bad_input);
    CHECK(c.reason == "thrust is not a finite number");  // admission's one check, world::check_input
    fake_client d;
    REQUIRE(join(g, d, hello()) != 0);
    g.tick();
    // A burst of 5 s of inputs at the limit is allowed (what queues while the server stalls).
    bool flood = false;
    for (uint32_t s = 1; s <= 200 && !flood; ++s) flood = !send_input(g, d, {s, 0, 0, 0});
    REQUIRE(flood);
    REQUIRE(d.rejected);
    CHECK(*d.rejected == protocol::RejectCode::rate_limit);
}

TEST_CASE("a player who leaves loses its body at the next tick", "[match]") {
    match::match g({}, world::asteroids_preset());
    fake_client c;
    REQUIRE(join(g, c, hello()) != 0);
    g.tick();
    const size_t with_player = g.state().bodies().size();
    say_bye(g, c, "test");
    g.tick();
    CHECK(g.state().bodies().size() == with_player - 1);
    CHECK(g.player_count() == 0);
}

TEST_CASE("a dropped player comes back to the same body within the grace period", "[match][reconnect]") {
    match::match_config config = make_config();
    config.reconnect_grace_s = 1;  // 60 ticks
    match::match g(config, world::asteroids_preset());
    fake_client first, second;
    const uint32_t id = join(g, first, hello(), "key-1");
    REQUIRE(id != 0);
    g.tick();
    const size_t bodies = g.state().bodies().size();
    drop(g, first);
    for (int k = 0; k < 30; ++k) g.tick();
    CHECK(g.state().bodies().size() == bodies);  // the body waits
    const uint32_t back = join(g, second, hello(), "key-1");
    REQUIRE(back != 0);
    CHECK(back == id);
    g.tick();
    REQUIRE(second.frames.size() == 1);
    auto welcome =
        protocol::decode_welcome(*protocol::verify_message(second.frames[0], protocol::server_frame_limits).value);
    REQUIRE(welcome);
    CHECK(welcome.value.player_id == id);
    CHECK(g.state().find(welcome.value.entity_id)->owner == id);
    CHECK(g.counters().reconnects == 1);
}

TEST_CASE("after the grace period a dropped player's body is removed", "[match][reconnect]") {
    match::match_config config = make_config();
    config.reconnect_grace_s = 0.5;  // 30 ticks
    match::match g(config, world::asteroids_preset());
    fake_client c, later;
    const uint32_t id = join(g, c, hello(), "key-2");
    REQUIRE(id != 0);
    g.tick();
    const size_t bodies = g.state().bodies().size();
    drop(g, c);
    for (int k = 0; k < 32; ++k) g.tick();
    CHECK(g.state().bodies().size() == bodies - 1);
    CHECK(g.player_count() == 0);
    // Coming back now is a new player.
    const uint32_t again = join(g, later, hello(), "key-2");
    REQUIRE(again != 0);
    CHECK(again != id);
}

TEST_CASE("a second connection with the same identity takes the player over", "[match][reconnect]") {
    match::match g(make_config(), world::asteroids_preset());
    fake_client first, second;
    const uint32_t id = join(g, first, hello(), "key-3");
    REQUIRE(id != 0);
    g.tick();
    REQUIRE(join(g, second, hello(), "key-3") == id);
    CHECK(first.bye.find("another connection") != std::string::npos);
    // The old connection's leave no longer touches the player.
    drop(g, first);
    CHECK(g.player_count() == 1);
    CHECK(g.counters().takeovers == 1);
}

TEST_CASE("a player without an identity or who says bye leaves at once", "[match][reconnect]") {
    match::match g(make_config(), world::asteroids_preset());
    fake_client anonymous, named;
    REQUIRE(join(g, anonymous, hello()) != 0);
    REQUIRE(join(g, named, hello(), "key-4") != 0);
    g.tick();
    drop(g, anonymous);
    say_bye(g, named, "client said bye");
    CHECK(g.player_count() == 0);
}

namespace {

// Ends its own connection from inside a send, as a transport may when its queue is full.
struct rejects_while_sending : fake_client {
    match::match* game = nullptr;
    void send(protocol::frame_bytes frame) override {
        fake_client::send(std::move(frame));
        if (game) game->reject(*this, {protocol::RejectCode::slow_consumer, "queue full"});
    }
};

size_t welcomes_in(const fake_client& c) {
    size_t n = 0;
    for (const auto& f : c.frames) {
        auto m = protocol::verify_message(f, protocol::server_frame_limits);
        if (m && m.value->payload_type() == protocol::Payload::Welcome) ++n;
    }
    return n;
}

}  // namespace

TEST_CASE("reconnects in one tick each get one Welcome though one is refused while it is sent", "[match][reconnect]") {
    match::match_config config = make_config();
    config.reconnect_grace_s = 10;
    match::match g(config, world::asteroids_preset());
    fake_client a1, b1, c1;
    REQUIRE(join(g, a1, hello(), "key-a") != 0);
    REQUIRE(join(g, b1, hello(), "key-b") != 0);
    REQUIRE(join(g, c1, hello(), "key-c") != 0);
    g.tick();
    drop(g, a1);
    drop(g, b1);
    drop(g, c1);
    g.tick();
    rejects_while_sending a2;
    fake_client b2, c2;
    a2.game = &g;
    REQUIRE(join(g, a2, hello(), "key-a") != 0);
    REQUIRE(join(g, b2, hello(), "key-b") != 0);
    REQUIRE(join(g, c2, hello(), "key-c") != 0);
    g.tick();  // a2's Welcome ends a2, and its player leaves the list being walked
    CHECK(a2.rejected == protocol::RejectCode::slow_consumer);
    CHECK(welcomes_in(b2) == 1);
    CHECK(welcomes_in(c2) == 1);
    g.tick();
    CHECK(welcomes_in(b2) == 1);
    CHECK(welcomes_in(c2) == 1);
}

namespace {

// Its first Welcome makes another client reconnect at once, from inside the send.
struct reconnects_another : fake_client {
    match::match* game = nullptr;
    fake_client* other = nullptr;
    void send(protocol::frame_bytes frame) override {
        fake_client::send(std::move(frame));
        if (game && other) {
            match::match& g = *game;
            game = nullptr;
            REQUIRE(join(g, *other, hello(), "key-e") != 0);
        }
    }
};

}  // namespace

TEST_CASE("a reconnect during another's Welcome gets its own Welcome next tick", "[match][reconnect]") {
    match::match_config config = make_config();
    config.reconnect_grace_s = 10;
    match::match g(config, world::asteroids_preset());
    fake_client d1, e1, e2;
    REQUIRE(join(g, d1, hello(), "key-d") != 0);
    REQUIRE(join(g, e1, hello(), "key-e") != 0);
    g.tick();
    drop(g, d1);
    drop(g, e1);
    reconnects_another d2;
    d2.game = &g;
    d2.other = &e2;
    REQUIRE(join(g, d2, hello(), "key-d") != 0);
    g.tick();  // d2's Welcome: e reconnects while the pending Welcomes are walked
    CHECK(welcomes_in(d2) == 1);
    g.tick();
    CHECK(welcomes_in(e2) == 1);
    CHECK(g.counters().reconnects == 2);
}

TEST_CASE("a snapshot rate that does not divide the tick rate is refused: the Welcome could not tell it", "[match]") {
    match::match_config config = make_config();
    config.snapshot_rate = 50;
    CHECK_THROWS_AS(match::match(config, world::asteroids_preset()), std::invalid_argument);
    config.snapshot_rate = 7;
    CHECK_THROWS_AS(match::match(config, world::asteroids_preset()), std::invalid_argument);
    config.snapshot_rate = 30;
    match::match ok(config, world::asteroids_preset());
    fake_client c;
    REQUIRE(join(ok, c, hello()) != 0);
    for (int k = 0; k < 13; ++k) ok.tick();
    auto welcome =
        protocol::decode_welcome(*protocol::verify_message(c.frames[0], protocol::server_frame_limits).value);
    REQUIRE(welcome);
    CHECK(welcome.value.snapshot_rate == 30);
    REQUIRE(c.snapshot_ticks.size() >= 2);
    CHECK(c.snapshot_ticks[1] - c.snapshot_ticks[0] == 60u / welcome.value.snapshot_rate);
}

TEST_CASE("under game rules the match tags each new body with the rules' kind and keeps score by name",
          "[match][rules]") {
    world::world_config config = world::asteroids_preset();
    config.rules = "asteroids";
    match::match g(make_config(2), config);
    fake_client c;
    const uint32_t player = join(g, c, hello());
    REQUIRE(player != 0);
    g.tick();
    const uint32_t ship = g.game_rules().body_of(player);
    REQUIRE(ship != 0);
    CHECK(g.body_kind(ship) == 1);
    CHECK(g.body_kind(1) == 2);  // the first rock
    // Fire (button bit 1): the bullet appears and is tagged in the same tick.
    protocol::input_msg in;
    in.sequence = 1;
    in.buttons = 1u << 1;
    REQUIRE(send_input(g, c, in));
    g.tick();
    const uint32_t bullet = g.state().bodies().back().id;
    CHECK(bullet > ship);
    CHECK(g.body_kind(bullet) == 3);
    const auto board = g.scoreboard();
    REQUIRE(board.size() == 1);
    CHECK(board[0].name == "tester");
    CHECK(board[0].line.shots == 1);
    CHECK(g.counters().shots == 1);
    // Sandbox rules tag nothing.
    match::match sandbox(make_config(2), world::asteroids_preset());
    fake_client d;
    REQUIRE(join(sandbox, d, hello()) != 0);
    sandbox.tick();
    CHECK(sandbox.body_kind(1) == 0);
    CHECK(sandbox.scoreboard().empty());
}

TEST_CASE("a connection's record lives as long as its match holds it, and names that match", "[match]") {
    fake_client c, taken_over;
    protocol::input_msg input{};
    input.sequence = 1;
    input.thrust = 1;
    {
        match::match first(make_config(), world::asteroids_preset());
        match::match second(make_config(), world::asteroids_preset());
        CHECK(c.record == nullptr);
        REQUIRE(join(first, c, hello(), "key-r") != 0);
        REQUIRE(c.record != nullptr);
        CHECK(c.record->owner == &first);
        CHECK(c.record->player != nullptr);
        first.tick();
        // A match that does not hold the connection ignores what it sends, whatever its record says.
        CHECK_FALSE(send_input(second, c, input));
        CHECK(second.counters().inputs_received == 0);
        CHECK(send_input(first, c, input));
        CHECK(first.counters().inputs_received == 1);

        // A takeover: the old connection is forgotten, the new one plays the same player.
        REQUIRE(join(first, taken_over, hello(), "key-r") != 0);
        CHECK(c.record == nullptr);
        REQUIRE(taken_over.record != nullptr);
        CHECK(taken_over.record->player != nullptr);
        input.sequence = 2;
        CHECK(send_input(first, taken_over, input));
        CHECK(first.counters().inputs_received == 2);
        CHECK_FALSE(send_input(first, c, input));  // the old connection's late bytes
    }
    // The match ended while holding the connection: its record went with it.
    CHECK(taken_over.record == nullptr);
}

TEST_CASE("a match that ends after a connection it holds writes nothing to it, and a copy holds no record", "[match]") {
    auto gone_first = std::make_unique<fake_client>();
    fake_client stays;
    {
        match::match g(make_config(), world::asteroids_preset());
        REQUIRE(join(g, *gone_first, hello(), "key-g") != 0);
        REQUIRE(join(g, stays, hello(), "key-s") != 0);
        const fake_client copy = stays;
        CHECK(copy.record == nullptr);  // a new connection, held by no match
        CHECK(stays.record != nullptr);
        gone_first.reset();  // freed while the match holds it: the match must not write to it (ASan)
    }
    CHECK(stays.record == nullptr);
}
