// Admission: every rule about what a client may send and when, each refusal with its typed
// code, driven through match::receive() as a transport drives it.
#include <catch2/catch.hpp>
#include <limits>
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
    std::string_view peer() const override { return "10.0.0.7:4242"; }
};

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
    config.max_name_bytes = 8;
    config.max_token_bytes = 16;
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
        if (token == "good") return match::token_verdict{"signed-bob", {}};
        return match::token_verdict{std::nullopt, "token forged"};
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
}

TEST_CASE("connections and handshakes beyond their limits are refused as server_full", "[match][admission]") {
    match::match_config config;
    config.max_connections = 3;
    config.max_pending_handshakes = 2;
    match::match m(config, small_world());
    client a, b, c, d, e;
    REQUIRE(m.connect(a));
    REQUIRE(m.connect(b));
    CHECK_FALSE(m.connect(c));
    CHECK(c.rejected == RejectCode::server_full);
    CHECK(c.detail == "too many connections waiting to say Hello");
    REQUIRE(join(m, a, hello()) != 0);  // no longer waiting
    REQUIRE(m.connect(d));
    CHECK_FALSE(m.connect(e));
    CHECK(e.detail == "too many connections");
    CHECK(m.connection_count() == 3);
}

TEST_CASE("a connection that never says Hello is refused after the handshake timeout, in ticks", "[match][admission]") {
    match::match_config config;
    config.handshake_timeout_s = 0.5;  // 30 ticks at 60 Hz
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
