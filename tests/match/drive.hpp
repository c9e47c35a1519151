#pragma once
// Drives a match as a transport does: each message is encoded, verified and handed to
// match::receive(), so that the tests go through admission exactly as bytes from a socket do.
#include <catch2/catch.hpp>
#include <optional>
#include <string>
#include <utility>

#include "protocol/decode.hpp"
#include "protocol/messages.hpp"
#include "protocol/verify.hpp"
#include "server/match/match.hpp"
#include "server/world/presets.hpp"

namespace arena::match_test {

// A connection that drops whatever the match sends it and keeps only why it was closed.
struct quiet_client : match::connection {
    quiet_client() = default;
    explicit quiet_client(std::string peer) : from(std::move(peer)) {}
    std::string from = "10.0.0.9:4000";
    std::optional<protocol::RejectCode> rejected;
    std::string detail;
    void send(protocol::frame_bytes) override {}
    void send_snapshot(const protocol::snapshot_encoder&, uint32_t) override {}
    void send_snapshot_frame(std::span<const uint8_t>) override {}
    void close(protocol::RejectCode code, std::string_view why) override {
        rejected = code;
        detail = why;
    }
    void close_with_bye(std::string_view) override {}
    std::string_view peer() const override { return from; }
};

// The asteroids preset without rocks: the players' ships alone.
inline world::world_config rockless_asteroids() {
    world::world_config w = world::asteroids_preset();
    w.rocks.count = 0;
    return w;
}

// Hands one encoded client message to the match; false: the match ended the connection.
inline bool deliver(match::match& m, match::connection& c, const protocol::frame_bytes& frame) {
    auto verified = protocol::verify_message(frame, protocol::client_frame_limits);
    REQUIRE(verified);
    return m.receive(c, *verified.value);
}

// The same, arrived at `arrival_ns` on the transport's clock (rates are measured in real time).
inline bool deliver_at(match::match& m, match::connection& c, const protocol::frame_bytes& frame, int64_t arrival_ns) {
    auto verified = protocol::verify_message(frame, protocol::client_frame_limits);
    REQUIRE(verified);
    return m.receive(c, *verified.value, arrival_ns);
}

// Connects `c` (when it is new) and sends its Hello; `identity` goes in the token, which an
// open server takes as the client's key. The player id (a spectator's: the id of its Welcome),
// or 0 when refused.
inline uint32_t join(match::match& m, match::connection& c, const protocol::hello_msg& hello,
                     const std::string& identity = {}) {
    if (m.player_of(c) == 0 && !m.connect(c)) return 0;
    const std::string token = identity.empty() ? hello.token : identity;
    if (!deliver(
            m, c,
            protocol::encode_hello(hello.protocol_version, hello.name, token, hello.delta_snapshots, hello.spectator)))
        return 0;
    return m.player_of(c);
}

// Sends one Input; false: refused (the connection is over).
inline bool send_input(match::match& m, match::connection& c, const protocol::input_msg& input) {
    return deliver(m, c, protocol::encode_input(input));
}

// The client says Bye and leaves at once.
inline void say_bye(match::match& m, match::connection& c, const std::string& reason = "done") {
    CHECK_FALSE(deliver(m, c, protocol::encode_bye(reason)));
}

// Verifies and decodes a snapshot frame the match sent; `storage` keeps the bytes the view
// points into.
inline protocol::snapshot_view read_snapshot(std::span<const uint8_t> bytes, protocol::frame_bytes& storage) {
    storage.assign(bytes.begin(), bytes.end());
    auto m = protocol::verify_message(storage, protocol::server_frame_limits);
    REQUIRE(m);
    auto snap = protocol::decode_snapshot(*m.value);
    REQUIRE(snap);
    return snap.value;
}

// The connection drops without a word.
inline void drop(match::match& m, match::connection& c) {
    m.disconnect(c, {match::close_cause::kind::connection_closed, {}, {}});
}

}  // namespace arena::match_test
