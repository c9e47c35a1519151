// Spectators (Hello.spectator): they join without a body, see the whole world and the game,
// send no Input, have a cap of their own and hold no identity. Driven through match::receive()
// as a transport drives it, in virtual time.
#include <algorithm>
#include <catch2/catch.hpp>
#include <optional>
#include <string>
#include <vector>

#include "match/drive.hpp"
#include "protocol/decode.hpp"
#include "protocol/verify.hpp"
#include "server/match/match.hpp"
#include "server/world/presets.hpp"

using namespace arena;
using namespace arena::match_test;
using protocol::RejectCode;

namespace {

// Keeps the Welcome, the last snapshot's bodies and scoreboard lines, and its last word.
struct watcher : match::connection {
    std::optional<protocol::welcome_info> welcome;
    std::vector<protocol::BodyState> bodies;  // the newest snapshot's
    std::vector<uint32_t> line_players;       // every scoreboard line's player, over all snapshots
    size_t snapshots = 0;
    bool delta_seen = false;
    std::optional<RejectCode> rejected;
    std::string detail;
    std::optional<std::string> bye;
    std::optional<protocol::match_result> result;
    std::string from = "10.0.0.9:5000";

    void send(protocol::frame_bytes frame) override {
        auto m = protocol::verify_message(frame, protocol::server_frame_limits);
        REQUIRE(m);
        if (auto w = protocol::decode_welcome(*m.value)) welcome = w.value;
    }
    void send_snapshot(const protocol::snapshot_encoder& s, uint32_t ack) override {
        send_snapshot_frame(s.frame_with_ack(ack));
    }
    void send_snapshot_frame(std::span<const uint8_t> bytes) override {
        protocol::frame_bytes frame;
        const protocol::snapshot_view snap = read_snapshot(bytes, frame);
        ++snapshots;
        delta_seen = delta_seen || snap.is_delta;
        bodies.assign(snap.bodies.begin(), snap.bodies.end());
        protocol::game_list game;
        REQUIRE(protocol::read_game(*snap.table, game).empty());
        for (const protocol::player_row& row : game.players) line_players.push_back(row.player);
    }
    void close(RejectCode code, std::string_view why) override {
        rejected = code;
        detail = why;
    }
    void close_with_bye(std::string_view reason) override { bye = reason; }
    void close_with_result(std::string_view reason, const protocol::match_result& r) override {
        bye = reason;
        result = r;
    }
    std::string_view peer() const override { return from; }
};

protocol::hello_msg player_hello(std::string name, std::string token = "") {
    return {protocol::protocol_version, std::move(name), std::move(token), true, false};
}

protocol::hello_msg spectator_hello(std::string name = "watcher", std::string token = "", bool delta = false) {
    return {protocol::protocol_version, std::move(name), std::move(token), delta, true};
}

// A view radius well below the world's size: a player sees its surroundings, a spectator all.
match::match_config config_with(uint32_t max_players = 8, uint32_t max_spectators = 16) {
    match::match_config c;
    c.admission.max_players = max_players;
    c.admission.max_spectators = max_spectators;
    c.view_radius = 60;
    return c;
}

// Each player sends one neutral input per tick (so that it is not idle); the spectators ping
// once a second, as the SDK does.
void run(match::match& m, std::vector<watcher*> players, std::vector<watcher*> spectators, uint32_t ticks) {
    for (uint32_t t = 0; t < ticks; ++t) {
        for (watcher* p : players)
            if (!p->rejected && !p->bye) REQUIRE(send_input(m, *p, {m.state().tick() + 1, 0, 0, 0}));
        if (m.state().tick() % 60 == 0)
            for (watcher* s : spectators)
                if (!s->rejected && !s->bye) REQUIRE(deliver(m, *s, protocol::encode_ping(t)));
        m.tick();
    }
}

// Asteroids with its rules, so that there is a scoreboard to hear.
world::world_config asteroids() {
    world::world_config w = world::asteroids_preset();
    w.rules = "asteroids";
    return w;
}

size_t owned_by(const std::vector<protocol::BodyState>& bodies, uint32_t owner) {
    return static_cast<size_t>(
        std::count_if(bodies.begin(), bodies.end(), [&](const protocol::BodyState& b) { return b.owner() == owner; }));
}

}  // namespace

TEST_CASE("a spectator is welcomed without a body and sees the whole world with the bots' bodies",
          "[match][spectator]") {
    match::match m(config_with(), asteroids());
    watcher ann, bob, eve;
    const uint32_t ann_id = join(m, ann, player_hello("ann"));
    const uint32_t bob_id = join(m, bob, player_hello("bob"));
    const uint32_t eve_id = join(m, eve, spectator_hello("eve", "", true));  // asks for deltas: gets BodyState
    REQUIRE(ann_id != 0);
    REQUIRE(bob_id != 0);
    REQUIRE(eve_id != 0);
    CHECK(eve_id != ann_id);
    CHECK(eve_id != bob_id);
    // Welcomed at once: there is no body to wait for.
    REQUIRE(eve.welcome);
    CHECK(eve.welcome->player_id == eve_id);
    CHECK(eve.welcome->entity_id == 0);
    CHECK(eve.welcome->view_radius == 0.0f);  // its snapshots hold every body
    CHECK(eve.welcome->world_config == m.world_config_json());

    run(m, {&ann, &bob}, {&eve}, 120);
    REQUIRE(ann.welcome);
    CHECK(ann.welcome->view_radius == 60.0f);
    CHECK(eve.snapshots == 40);  // every third tick, as a player's
    CHECK_FALSE(eve.delta_seen);
    // The whole world, the players' ships among it, and no body of its own.
    CHECK(eve.bodies.size() == m.state().bodies().size());
    CHECK(owned_by(eve.bodies, ann_id) >= 1);
    CHECK(owned_by(eve.bodies, bob_id) >= 1);
    CHECK(owned_by(eve.bodies, eve_id) == 0);
    CHECK(ann.bodies.size() < eve.bodies.size());  // a player sees its surroundings only
    // It hears the scoreboard, and is not on it.
    CHECK(std::count(eve.line_players.begin(), eve.line_players.end(), ann_id) >= 1);
    CHECK(std::count(eve.line_players.begin(), eve.line_players.end(), eve_id) == 0);
    for (const auto& line : m.scoreboard()) CHECK(line.line.player != eve_id);
    // Counted apart from the players.
    const match::match_counters c = m.counters();
    CHECK(c.spectators == 1);
    CHECK(c.players == 2);
    CHECK(c.joins == 2);
    CHECK(m.live_player_count() == 2);

    // The end of the match reaches it like the players, with the result.
    m.shut_down("match over");
    REQUIRE(eve.bye);
    CHECK(*eve.bye == "match over");
    REQUIRE(ann.bye);
    CHECK(m.counters().spectators == 0);
}

TEST_CASE("an Input from a spectator is refused as bad_request and the others play on", "[match][spectator]") {
    match::match m(config_with(), asteroids());
    watcher ann, eve;
    REQUIRE(join(m, ann, player_hello("ann")) != 0);
    REQUIRE(join(m, eve, spectator_hello()) != 0);
    run(m, {&ann}, {}, 3);
    CHECK_FALSE(send_input(m, eve, {1, 1, 0, 0}));
    REQUIRE(eve.rejected);
    CHECK(*eve.rejected == RejectCode::bad_request);
    CHECK(eve.detail == "Input from a spectator, who has no body");
    CHECK(m.counters().spectators == 0);
    CHECK(m.counters().rejects.at(RejectCode::bad_request) == 1);
    const size_t before = ann.snapshots;
    run(m, {&ann}, {}, 6);
    CHECK(ann.snapshots == before + 2);
    CHECK_FALSE(ann.rejected);
}

TEST_CASE("spectators have a cap of their own and take no player's slot", "[match][spectator]") {
    SECTION("--max-spectators 2: the third is refused as server_full, a player still joins") {
        match::match m(config_with(1, 2), asteroids());
        watcher a, b, c, player, late;
        REQUIRE(join(m, a, spectator_hello("a")) != 0);
        REQUIRE(join(m, b, spectator_hello("b")) != 0);
        CHECK(join(m, c, spectator_hello("c")) == 0);
        REQUIRE(c.rejected);
        CHECK(*c.rejected == RejectCode::server_full);
        CHECK(c.detail == "server full (2 spectators)");
        // The one player slot is free although two spectators watch.
        REQUIRE(join(m, player, player_hello("p")) != 0);
        CHECK(join(m, late, player_hello("q")) == 0);
        CHECK(late.detail == "server full (1 players)");
        // A spectator that leaves gives its slot back.
        say_bye(m, a);
        watcher d;
        CHECK(join(m, d, spectator_hello("d")) != 0);
        CHECK(m.counters().spectators == 2);
    }
    SECTION("--max-spectators 0: every spectator is refused, players join") {
        match::match m(config_with(4, 0), asteroids());
        watcher s, p;
        CHECK(join(m, s, spectator_hello()) == 0);
        REQUIRE(s.rejected);
        CHECK(*s.rejected == RejectCode::server_full);
        CHECK(s.detail == "this server admits no spectators");
        CHECK(join(m, p, player_hello("p")) != 0);
    }
}

TEST_CASE("a spectator with a player's name and token takes nothing over and is not taken over",
          "[match][spectator][admission]") {
    SECTION("open server: the token is the player's key, not the spectator's") {
        match::match m(config_with(), asteroids());
        watcher ann, ann_watching, ann_again;
        const uint32_t ann_id = join(m, ann, player_hello("ann", "key"));
        REQUIRE(ann_id != 0);
        run(m, {&ann}, {}, 1);
        const uint32_t watching_id = join(m, ann_watching, spectator_hello("ann", "key"));
        REQUIRE(watching_id != 0);
        CHECK(watching_id != ann_id);
        CHECK_FALSE(ann.bye);  // the player keeps its connection
        // The player's key still takes the player over, never the spectator.
        REQUIRE(join(m, ann_again, player_hello("ann", "key")) == ann_id);
        CHECK(ann.bye);
        CHECK_FALSE(ann_watching.bye);
        CHECK(m.counters().takeovers == 1);
        CHECK(m.counters().spectators == 1);
    }
    SECTION("signed tokens: a good token lets a spectator watch under the signed name; a bad one does not") {
        auto check = [](std::string_view token) {
            if (token == "good") return arena::result<match::signed_token>::success({"signed-bob", ""});
            return arena::result<match::signed_token>::failure("token forged");
        };
        match::match m(config_with(), asteroids(), {}, check);
        watcher bob, bob_watching, forged;
        const uint32_t bob_id = join(m, bob, player_hello("bob", "good"));
        REQUIRE(bob_id != 0);
        run(m, {&bob}, {}, 1);
        REQUIRE(join(m, bob_watching, spectator_hello("bob", "good")) != 0);
        CHECK_FALSE(bob.bye);
        CHECK(join(m, forged, spectator_hello("eve", "bad")) == 0);
        REQUIRE(forged.rejected);
        CHECK(*forged.rejected == RejectCode::unauthorized);
        // The player drops and comes back: its own body, not the spectator's connection.
        drop(m, bob);
        watcher bob_back;
        CHECK(join(m, bob_back, player_hello("bob", "good")) == bob_id);
        CHECK(m.counters().reconnects == 1);
        CHECK_FALSE(bob_watching.bye);
    }
}

TEST_CASE("a spectator's Pings keep it from the idle timeout, and a silent one times out", "[match][spectator]") {
    match::match m(config_with(), asteroids());  // idle timeout 5 s: 300 ticks
    watcher pinging, silent;
    REQUIRE(join(m, pinging, spectator_hello("p")) != 0);
    REQUIRE(join(m, silent, spectator_hello("s")) != 0);
    run(m, {}, {&pinging}, 400);
    CHECK_FALSE(pinging.rejected);
    REQUIRE(silent.rejected);
    CHECK(*silent.rejected == RejectCode::timeout);
    CHECK(silent.detail == "no Ping within the idle timeout");
    CHECK(m.counters().spectators == 1);
}
