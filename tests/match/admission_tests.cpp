// Admission: every rule about what a client may send and when, each refusal with its typed
// code, driven through match::receive() as a transport drives it.
#include <algorithm>
#include <catch2/catch.hpp>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "match/drive.hpp"
#include "protocol/decode.hpp"
#include "protocol/framing.hpp"
#include "server/match/admission.hpp"
#include "server/world/presets.hpp"

using namespace arena;
using namespace arena::match_test;
using protocol::RejectCode;

namespace {

// Remembers the last word it was given and the control frames before it.
struct client : match::connection {
    std::vector<protocol::frame_bytes> frames;
    std::optional<RejectCode> rejected;
    std::string detail;
    std::optional<std::string> bye;
    void send(protocol::frame_bytes frame) override { frames.push_back(std::move(frame)); }
    void send_snapshot(const protocol::snapshot_encoder&, uint32_t) override {}
    void send_snapshot_frame(std::span<const uint8_t>) override {}
    void close(RejectCode code, std::string_view why) override {
        rejected = code;
        detail = why;
    }
    void close_with_bye(std::string_view reason) override { bye = reason; }
    std::string from = "10.0.0.7:4242";
    std::string_view peer() const override { return from; }
};

client from(const std::string& address) {
    client c;
    c.from = address;
    return c;
}

protocol::hello_msg hello(std::string name = "ann", std::string token = "") {
    return {protocol::protocol_version, std::move(name), std::move(token)};
}

world::world_config small_world() {
    world::world_config w = world::asteroids_preset();
    w.rocks.count = 2;
    return w;
}

}  // namespace

TEST_CASE("messages out of order are refused as bad_request, each with its detail", "[match][admission]") {
    match::match m({}, small_world());
    client input_first, ping_first, twice, odd;
    REQUIRE(m.connect(input_first));
    CHECK_FALSE(send_input(m, input_first, {1, 0, 0, 0}));
    CHECK(input_first.rejected == RejectCode::bad_request);
    CHECK(input_first.detail == "Input before Hello");

    REQUIRE(m.connect(ping_first));
    CHECK_FALSE(deliver(m, ping_first, protocol::encode_ping(5)));
    CHECK(ping_first.detail == "Ping before Hello");

    REQUIRE(join(m, twice, hello()) != 0);
    CHECK_FALSE(deliver(m, twice, protocol::encode_hello(protocol::protocol_version, "ann", "")));
    CHECK(twice.rejected == RejectCode::bad_request);
    CHECK(twice.detail == "a second Hello");

    REQUIRE(m.connect(odd));
    CHECK_FALSE(deliver(m, odd, protocol::encode_pong(1, 2)));
    CHECK(odd.detail == "unexpected Pong from a client");

    const auto counters = m.counters();
    CHECK(counters.rejects.at(RejectCode::bad_request) == 4);
    CHECK(counters.closes.at("bad_request") == 4);
    CHECK(m.connection_count() == 0);
}

TEST_CASE("the Hello's limits: version, name and token length, each with its code", "[match][admission]") {
    match::match_config config;
    config.admission.max_name_bytes = 8;
    config.admission.max_token_bytes = 16;
    match::match m(config, small_world());
    client old, long_name, long_token, fine;
    CHECK(join(m, old, {7, "ann", ""}) == 0);
    CHECK(old.rejected == RejectCode::version_mismatch);
    CHECK(join(m, long_name, hello("a-long-name")) == 0);
    CHECK(long_name.rejected == RejectCode::bad_request);
    CHECK(long_name.detail == "name longer than 8 bytes");
    CHECK(join(m, long_token, hello("ann", std::string(17, 't'))) == 0);
    CHECK(long_token.detail == "token longer than 16 bytes");
    CHECK(join(m, fine, hello("ann", std::string(16, 't'))) != 0);
}

TEST_CASE("a token checker decides who the player is, and a refused token is unauthorized", "[match][admission]") {
    auto check = [](std::string_view token) {
        if (token == "good") return arena::result<match::signed_token>::success({"signed-bob", ""});
        return arena::result<match::signed_token>::failure("token forged");
    };
    std::vector<std::string> lines;
    match::match m({}, small_world(), match::logger([&](std::string_view l) { lines.emplace_back(l); }), check);
    client forged, signed_in, again;
    CHECK(join(m, forged, hello("eve", "bad")) == 0);
    CHECK(forged.rejected == RejectCode::unauthorized);
    CHECK(forged.detail == "token forged");
    const uint32_t id = join(m, signed_in, hello("claims-alice", "good"));
    REQUIRE(id != 0);
    // The signed name is the identity: the same token again takes the player over.
    CHECK(join(m, again, hello("whoever", "good")) == id);
    CHECK(signed_in.bye == "signed in from another connection");
    CHECK(m.counters().closes.at("signed in from another connection") == 1);
    CHECK(std::find(lines.begin(), lines.end(), "reject 10.0.0.7:4242 code=unauthorized reason=token forged") !=
          lines.end());
    // The log names the signed player, not the name the Hello claimed.
    CHECK(std::find(lines.begin(), lines.end(), "hello player=1 name=signed-bob from 10.0.0.7:4242") != lines.end());
    for (const std::string& l : lines) CHECK(l.find("claims-alice") == std::string::npos);
}

TEST_CASE("full handshake slots: the oldest waiting connection of the busiest address makes room",
          "[match][admission]") {
    match::match_config config;
    config.admission.max_pending_handshakes = 4;
    match::match m(config, small_world());
    std::vector<client> idle(5, from("10.6.6.6:1000"));
    for (size_t k = 0; k < 4; ++k) REQUIRE(m.connect(idle[k]));
    // An honest player when every slot is taken by idle sockets: it gets in, the oldest idle one goes.
    client honest = from("10.0.0.7:5000");
    REQUIRE(m.connect(honest));
    CHECK(idle[0].rejected == RejectCode::too_many_waiting);
    CHECK(idle[0].detail == "too many connections waiting to say Hello; a newer one took this slot");
    CHECK_FALSE(idle[1].rejected);
    // Another waiting connection elsewhere keeps its slot: the address holding the most pays.
    client other = from("10.0.0.8:5000");
    REQUIRE(m.connect(other));
    CHECK(idle[1].rejected == RejectCode::too_many_waiting);
    REQUIRE(m.connect(idle[4]));  // the attacker reopens: it pushes out its own oldest
    CHECK(idle[2].rejected == RejectCode::too_many_waiting);
    CHECK_FALSE(honest.rejected);
    CHECK_FALSE(other.rejected);
    REQUIRE(join(m, honest, hello("honest")) != 0);
    REQUIRE(join(m, other, hello("other")) != 0);
    // A server that is not full never says server_full.
    CHECK(m.counters().rejects.count(RejectCode::server_full) == 0);
    CHECK(m.counters().rejects.at(RejectCode::too_many_waiting) == 3);
}

TEST_CASE("idle sockets reopened as they time out keep no player out", "[match][admission]") {
    match::match_config config;
    config.admission.max_pending_handshakes = 64;
    config.admission.handshake_timeout = std::chrono::seconds(5);
    config.admission.idle_timeout = {};  // the players here send no Input
    match::match m(config, small_world());
    std::vector<std::unique_ptr<client>> attackers, players;
    auto reopen = [&] {
        size_t waiting = 0;
        for (auto& a : attackers) waiting += !a->rejected;
        while (waiting++ < 64) {
            attackers.push_back(std::make_unique<client>(from("10.6.6.6:1")));
            REQUIRE(m.connect(*attackers.back()));
        }
    };
    size_t joined = 0;
    for (int second = 0; second < 12; ++second) {
        for (int t = 0; t < 60; ++t) {
            reopen();
            if (t % 6 == 0) {  // ten new players a second, each between the attacker's reconnects
                players.push_back(std::make_unique<client>(from("10.0.0.7:1")));
                if (m.connect(*players.back())) {
                    reopen();
                    joined += join(m, *players.back(), hello("player")) != 0;
                }
            }
            m.tick();
        }
    }
    CHECK(players.size() == 120);
    CHECK(joined == 64);  // every slot of the match filled
    CHECK(m.live_player_count() == 64);
    size_t full = 0;
    for (auto& p : players) full += p->rejected == RejectCode::server_full;
    CHECK(full == 120 - 64);  // and only then server_full
}

TEST_CASE("200 players connecting at once to a 256-player server all get in", "[match][admission]") {
    match::match_config config;
    config.admission.max_players = 256;
    match::match m(config, small_world());
    std::vector<client> bots(200, from("127.0.0.1:1"));
    for (auto& b : bots) REQUIRE(m.connect(b));  // the transport accepts before any Hello is read
    size_t joined = 0;
    for (auto& b : bots) joined += join(m, b, hello("bot")) != 0;
    CHECK(joined == 200);
    CHECK(m.rules().pending_limit() == 272);
}

TEST_CASE("connections beyond max-connections: waiting ones make room, players never", "[match][admission]") {
    match::match_config config;
    config.admission.max_connections = 3;
    match::match m(config, small_world());
    client a, b, c, d, e;
    REQUIRE(join(m, a, hello()) != 0);
    REQUIRE(join(m, b, hello()) != 0);
    REQUIRE(m.connect(c));
    REQUIRE(m.connect(d));  // c was waiting: it makes room
    CHECK(c.rejected == RejectCode::too_many_waiting);
    REQUIRE(join(m, d, hello()) != 0);
    CHECK_FALSE(m.connect(e));  // three players: nobody waiting could make room
    CHECK(e.rejected == RejectCode::server_full);
    CHECK(e.detail == "too many connections");
    CHECK(m.connection_count() == 3);
}

TEST_CASE("bodies in the reconnect grace do not keep a new player out: the oldest is given up", "[match][admission]") {
    match::match_config config;
    config.admission.max_players = 4;
    config.reconnect_grace_s = 10;
    std::vector<std::string> lines;
    match::match m(config, small_world(), match::logger([&](std::string_view l) { lines.emplace_back(l); }));
    // Squatters: join with a fresh token, take the Welcome, drop without Bye.
    std::vector<client> squatters(4);
    for (size_t k = 0; k < 4; ++k) {
        REQUIRE(join(m, squatters[k], hello("s"), "squat-" + std::to_string(k)) != 0);
        m.tick();
        m.disconnect(squatters[k], {match::close_cause::kind::connection_closed, {}, {}});
    }
    CHECK(m.player_count() == 4);
    CHECK(m.live_player_count() == 0);
    CHECK(m.players_in_grace() == 4);
    std::vector<client> honest(5);
    for (size_t k = 0; k < 4; ++k) REQUIRE(join(m, honest[k], hello("h")) != 0);
    CHECK(m.live_player_count() == 4);
    CHECK(m.players_in_grace() == 0);
    CHECK(std::count(lines.begin(), lines.end(),
                     "leave player=1 name=s reason=reconnect grace given up: a new player needed the slot") == 1);
    // Full of live players: now, and only now, server_full.
    CHECK(join(m, honest[4], hello("h")) == 0);
    CHECK(honest[4].rejected == RejectCode::server_full);
}

TEST_CASE("a joined client that sends no Input is dropped after the idle timeout", "[match][admission]") {
    match::match_config config;
    config.admission.idle_timeout = std::chrono::milliseconds(500);  // 30 ticks at 60 Hz
    match::match m(config, small_world());
    client silent, talks, stops;
    REQUIRE(join(m, silent, hello()) != 0);
    REQUIRE(join(m, talks, hello()) != 0);
    REQUIRE(join(m, stops, hello()) != 0);
    for (uint32_t t = 1; t <= 29; ++t) {
        REQUIRE(send_input(m, talks, {t, 0, 0, 0}));
        if (t <= 10) REQUIRE(send_input(m, stops, {t, 0, 0, 0}));
        m.tick();
    }
    CHECK_FALSE(silent.rejected);
    m.tick();
    CHECK(silent.rejected == RejectCode::timeout);
    CHECK(silent.detail == "no Input within the idle timeout");
    CHECK_FALSE(stops.rejected);  // its last Input came at tick 9
    for (uint32_t t = 30; t <= 60; ++t) {
        REQUIRE(send_input(m, talks, {t, 0, 0, 0}));
        m.tick();
    }
    CHECK(stops.rejected == RejectCode::timeout);
    CHECK_FALSE(talks.rejected);
    CHECK(m.player_count() == 1);
}

TEST_CASE("the input rate is measured in real time: a stall's queued inputs are not a flood", "[match][admission]") {
    match::match m({}, small_world());  // 130 inputs per second
    client honest, flood;
    REQUIRE(join(m, honest, hello()) != 0);
    REQUIRE(join(m, flood, hello()) != 0);
    const int64_t tick_ns = 1'000'000'000 / 60;
    uint32_t seq = 0;
    for (int t = 0; t < 120; ++t) REQUIRE(deliver_at(m, honest, protocol::encode_input({++seq, 0, 0, 0}), t * tick_ns));
    // The server stood still 3 s: 180 inputs arrive together when it reads again.
    const int64_t resumed = 123 * tick_ns + 3'000'000'000;
    for (int k = 0; k < 180; ++k) REQUIRE(deliver_at(m, honest, protocol::encode_input({++seq, 0, 0, 0}), resumed));
    for (int t = 1; t <= 120; ++t)
        REQUIRE(deliver_at(m, honest, protocol::encode_input({++seq, 0, 0, 0}), resumed + t * tick_ns));
    CHECK_FALSE(honest.rejected);
    // Sustained at ten times the limit, a client runs out of its burst within a second.
    bool refused = false;
    int sent = 0;
    for (; sent < 1300 && !refused; ++sent)
        refused = !deliver_at(m, flood, protocol::encode_input({static_cast<uint32_t>(sent + 1), 0, 0, 0}),
                              static_cast<int64_t>(sent) * 1'000'000'000 / 1300);
    CHECK(refused);
    CHECK(flood.rejected == RejectCode::rate_limit);
    CHECK(sent < 1300);
}

TEST_CASE("a burst of Pings is refused as ping_limit, one a second is answered for ever", "[match][admission]") {
    match::match m({}, small_world());
    client steady, burst;
    REQUIRE(join(m, steady, hello()) != 0);
    REQUIRE(join(m, burst, hello()) != 0);
    for (int s = 0; s < 100; ++s)
        REQUIRE(deliver_at(m, steady, protocol::encode_ping(s), static_cast<int64_t>(s) * 1'000'000'000));
    CHECK(steady.frames.size() == 100);  // a Pong each
    int answered = 0;
    for (int k = 0; k < 1000; ++k) {
        if (!deliver_at(m, burst, protocol::encode_ping(k), 5'000'000'000)) break;
        ++answered;
    }
    CHECK(answered == 20);
    CHECK(burst.rejected == RejectCode::ping_limit);
    CHECK(m.counters().rejects.count(RejectCode::slow_consumer) == 0);
}

TEST_CASE("names that would forge or cut log lines are refused, a Bye reason is escaped", "[match][admission]") {
    std::vector<std::string> lines;
    match::match m({}, small_world(), match::logger([&](std::string_view l) { lines.emplace_back(l); }));
    client newline, nul, latin1, fine;
    CHECK(join(m, newline, hello("eve\nINFO join player=1 name=admin")) == 0);
    CHECK(newline.rejected == RejectCode::bad_request);
    CHECK(newline.detail == "name has a control character at byte 3 (0x0a)");
    CHECK(join(m, nul, hello(std::string("ad\0min", 6))) == 0);
    CHECK(nul.detail == "name has a control character at byte 2 (0x00)");
    CHECK(join(m, latin1, hello("caf\xe9")) == 0);
    CHECK(latin1.detail == "name is not valid UTF-8 at byte 3 (0xe9)");
    REQUIRE(join(m, fine, hello("Zo\xc3\xab")) != 0);
    m.tick();
    CHECK_FALSE(deliver(m, fine, protocol::encode_bye("bye\nINFO leave player=9\x01\xff")));
    for (const std::string& l : lines) {
        CHECK(l.find('\n') == std::string::npos);
        CHECK(l.find('\0') == std::string::npos);
    }
    CHECK(std::find(lines.begin(), lines.end(),
                    "leave player=1 name=Zo\xc3\xab reason=client said bye: bye\\x0aINFO leave player=9\\x01\\xff") !=
          lines.end());
}

TEST_CASE("a connection that never says Hello is refused after the handshake timeout, in ticks", "[match][admission]") {
    match::match_config config;
    config.admission.handshake_timeout = std::chrono::milliseconds(500);  // 30 ticks at 60 Hz
    match::match m(config, small_world());
    client slow, quick;
    REQUIRE(m.connect(slow));
    REQUIRE(m.connect(quick));
    REQUIRE(join(m, quick, hello()) != 0);
    for (int k = 0; k < 29; ++k) m.tick();
    CHECK_FALSE(slow.rejected);
    m.tick();
    CHECK(slow.rejected == RejectCode::timeout);
    CHECK(slow.detail == "no Hello within the handshake timeout");
    CHECK_FALSE(quick.rejected);
}

TEST_CASE("a stale input is ignored and counted, and a Ping gets a Pong with the tick", "[match][admission]") {
    match::match m({}, small_world());
    client c;
    REQUIRE(join(m, c, hello()) != 0);
    m.tick();
    REQUIRE(send_input(m, c, {5, 0.5f, 0, 0}));
    REQUIRE(send_input(m, c, {5, 0.5f, 0, 0}));
    REQUIRE(send_input(m, c, {4, 0.5f, 0, 0}));
    CHECK(m.counters().stale_inputs == 2);
    CHECK(m.counters().inputs_received == 3);
    c.frames.clear();
    REQUIRE(deliver(m, c, protocol::encode_ping(77)));
    REQUIRE(c.frames.size() == 1);
    auto pong = protocol::decode_pong(*protocol::verify_message(c.frames[0], protocol::server_frame_limits).value);
    REQUIRE(pong);
    CHECK(pong.value.client_time == 77);
    CHECK(pong.value.server_tick == m.state().tick());
}

TEST_CASE("while draining a Hello is refused as shutting_down, and shut_down says Bye to all", "[match][admission]") {
    match::match m({}, small_world());
    client playing, waiting, late;
    REQUIRE(join(m, playing, hello()) != 0);
    REQUIRE(m.connect(waiting));
    REQUIRE(m.connect(late));
    m.shut_down("server terminated (SIGTERM)");
    CHECK(playing.bye == "server terminated (SIGTERM)");
    CHECK(waiting.bye == "server terminated (SIGTERM)");
    CHECK(m.counters().closes.at("server terminated (SIGTERM)") == 3);
    CHECK(m.draining());
    client after;
    CHECK(join(m, after, hello()) == 0);
    CHECK(after.rejected == RejectCode::shutting_down);
}

TEST_CASE("a transport's unreadable bytes are typed by the frame reader, not by their text", "[match][admission]") {
    protocol::frame_reader big;
    const std::vector<uint8_t> huge_prefix{0xff, 0xff, 0xff, 0x7f};
    big.feed(huge_prefix);
    REQUIRE(big.failed());
    CHECK(match::admission::unreadable(big).code == RejectCode::too_large);
    protocol::frame_reader tiny;
    const std::vector<uint8_t> zero_prefix{0, 0, 0, 0};
    tiny.feed(zero_prefix);
    REQUIRE(tiny.failed());
    CHECK(match::admission::unreadable(tiny).code == RejectCode::bad_request);
    const match::rejection unverified = match::admission::unverified("bad union tag");
    CHECK(unverified.code == RejectCode::bad_request);
    CHECK(unverified.detail == "frame failed verification: bad union tag");
}

TEST_CASE("close causes give the log's text and the counters' key", "[match][admission]") {
    using kind = match::close_cause::kind;
    const match::close_cause nan = match::close_cause::of({RejectCode::bad_input, "thrust is not a finite number"});
    CHECK(nan.text() == "bad_input: thrust is not a finite number");
    CHECK(nan.key() == "bad_input");
    CHECK_FALSE(nan.connection_lost());
    const match::close_cause bye{kind::client_bye, {}, "done"};
    CHECK(bye.text() == "client said bye: done");
    CHECK(bye.key() == "client said bye");
    const match::close_cause eof{kind::connection_closed, {}, {}};
    CHECK(eof.text() == "connection closed");
    CHECK(eof.connection_lost());
    const match::close_cause mid{kind::closed_mid_frame, {}, {}};
    CHECK(mid.key() == "connection closed mid-frame");
    const match::close_cause err{kind::socket_error, {}, "Connection reset by peer"};
    CHECK(err.text() == "socket error: Connection reset by peer");
    CHECK(err.key() == "socket error");
    const match::close_cause write{kind::write_failed, {}, "Broken pipe"};
    CHECK(write.key() == "write failed");
    CHECK(write.connection_lost());
    const match::close_cause stop{kind::shutdown, {}, "match over (--duration reached)"};
    CHECK(stop.key() == "match over (--duration reached)");
    CHECK(stop.text() == stop.key());
}
