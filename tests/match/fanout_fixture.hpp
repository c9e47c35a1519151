#pragma once
// The fixture the snapshot fan-out tests share: a match of delta clients that record what
// they are sent, and the view a test computes on its own from the world (by brute force,
// quantised) to compare with what a client decoded.

#include <algorithm>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "match/drive.hpp"
#include "protocol/decode.hpp"
#include "protocol/delta/quantize.hpp"
#include "protocol/delta/receiver.hpp"
#include "protocol/verify.hpp"
#include "server/match/match.hpp"
#include "server/match/shape_wire.hpp"
#include "server/world/broadphase.hpp"
#include "server/world/presets.hpp"
#include "server/world/rng.hpp"

namespace fanout_fixture {

using namespace arena;
using protocol::delta::quantized_body;

constexpr uint16_t tick_rate = 60;
constexpr uint32_t snapshot_interval = 3;  // 60 Hz ticks, 20 Hz snapshots

inline match::match_config delta_config(float view_radius, uint32_t delta_history = 32) {
    match::match_config c;
    c.tick_rate = tick_rate;
    c.snapshot_rate = tick_rate / snapshot_interval;
    c.view_radius = view_radius;
    c.delta_history = delta_history;
    return c;
}

// Ticks a snapshot stays usable as a baseline: the server keeps the last delta_history.
inline uint32_t kept_ticks(const match::match_config& c) {
    return c.delta_history * snapshot_interval;
}

inline protocol::hello_msg hello(bool delta) {
    return {protocol::protocol_version, "tester", "", delta};
}

// Keeps what the match sends; the test decides what the client makes of it.
struct recording_client : match::connection {
    std::vector<protocol::frame_bytes> control;    // Welcome, in order
    std::vector<protocol::frame_bytes> snapshots;  // not yet looked at
    bool closed = false;
    void send(protocol::frame_bytes frame) override { control.push_back(std::move(frame)); }
    void send_snapshot(const protocol::snapshot_encoder& s, uint32_t ack) override {
        snapshots.push_back(s.frame_with_ack(ack));
    }
    void send_snapshot_frame(std::span<const uint8_t> frame) override {
        snapshots.emplace_back(frame.begin(), frame.end());
    }
    void close(protocol::RejectCode, std::string_view) override { closed = true; }
    void close_with_bye(std::string_view) override { closed = true; }
    std::string_view peer() const override { return "test"; }
};

// The body a Welcome gave this client; 0 before one came.
inline uint32_t welcomed_body(const recording_client& c) {
    for (const protocol::frame_bytes& frame : c.control) {
        auto message = protocol::verify_message(frame, protocol::server_frame_limits);
        REQUIRE(message);
        if (auto welcome = protocol::decode_welcome(*message.value)) return welcome.value.entity_id;
    }
    return 0;
}

// A snapshot frame as a client reads it: verified, then decoded in place (it points into frame).
inline protocol::snapshot_view read_snapshot(const protocol::frame_bytes& frame) {
    auto message = protocol::verify_message(frame, protocol::server_frame_limits);
    REQUIRE(message);
    auto snapshot = protocol::decode_snapshot(*message.value);
    INFO(snapshot.error);
    REQUIRE(snapshot);
    return snapshot.value;
}

inline protocol::BodyState body_state(const world::body& b) {
    return {b.id, b.owner, b.position.x(), b.position.y(), b.velocity.x(), b.velocity.y(), b.angle, b.angular_velocity};
}

// view_index.hpp's definition by brute force: the own body and every body whose circle comes
// within `radius` of its centre, the shortest way round; every body when radius is 0. The
// test is the index's own float expression, so that bodies on the edge agree.
inline std::vector<const world::body*> bodies_in_view(const world::world& w, uint32_t own_id, float radius) {
    const world::body* own = w.find(own_id);
    REQUIRE(own != nullptr);
    std::vector<const world::body*> view;
    for (const world::body& b : w.bodies()) {
        const float limit = radius + b.radius;
        if (radius <= 0 || world::displacement(own->position, b.position, w.config()).squaredNorm() <= limit * limit)
            view.push_back(&b);
    }
    return view;
}

inline std::vector<quantized_body> quantized_view(const world::world& w, uint32_t own_id, float radius) {
    std::vector<quantized_body> view;
    for (const world::body* b : bodies_in_view(w, own_id, radius)) {
        view.push_back(protocol::delta::quantize(body_state(*b)));
    }
    return view;
}

inline std::vector<uint32_t> ids_of(std::span<const quantized_body> bodies) {
    std::vector<uint32_t> ids;
    for (const quantized_body& b : bodies) ids.push_back(b.id);
    return ids;
}

inline std::vector<uint32_t> ids_of(std::span<const protocol::BodyState> bodies) {
    std::vector<uint32_t> ids;
    for (const protocol::BodyState& b : bodies) ids.push_back(b.id());
    return ids;
}

inline std::vector<uint32_t> ids_of(std::span<const world::body* const> bodies) {
    std::vector<uint32_t> ids;
    for (const world::body* b : bodies) ids.push_back(b->id);
    return ids;
}

inline std::vector<uint32_t> ids_of(std::span<const world::body> bodies) {
    std::vector<uint32_t> ids;
    for (const world::body& b : bodies) ids.push_back(b.id);
    return ids;
}

// A BodyState snapshot (a client without delta_snapshots) holds its view's bodies, floats exact.
inline void check_full_view(const protocol::snapshot_view& s, const world::world& w, uint32_t own_id, float radius) {
    REQUIRE_FALSE(s.is_delta);
    REQUIRE(s.baseline_tick == 0);
    const std::vector<const world::body*> view = bodies_in_view(w, own_id, radius);
    REQUIRE(ids_of(s.bodies) == ids_of(view));
    size_t inexact = 0;
    for (size_t i = 0; i < view.size(); ++i) {
        const protocol::BodyState& got = s.bodies[i];
        const protocol::BodyState want = body_state(*view[i]);
        const bool same = got.owner() == want.owner() && got.x() == want.x() && got.y() == want.y() &&
                          got.vx() == want.vx() && got.vy() == want.vy() && got.angle() == want.angle() &&
                          got.angular_velocity() == want.angular_velocity();
        if (!same) ++inexact;
    }
    REQUIRE(inexact == 0);
}

// Decodes a delta snapshot and requires it to be exactly the view computed from the world.
inline std::vector<uint32_t> decode_and_check(protocol::delta::receiver& rx, const protocol::snapshot_view& s,
                                              const world::world& w, uint32_t own_id, float radius) {
    REQUIRE(s.is_delta);
    auto decoded = rx.receive(s);
    INFO(decoded.error);
    REQUIRE(decoded);
    const std::vector<quantized_body> expected = quantized_view(w, own_id, radius);
    REQUIRE(ids_of(decoded.value) == ids_of(expected));
    REQUIRE(std::ranges::equal(decoded.value, expected));
    return ids_of(expected);
}

struct decoded_snapshot {
    uint32_t tick = 0;
    uint32_t baseline_tick = 0;
    std::vector<uint32_t> ids;  // of the bodies in the view
};

// A match and one delta client that decodes every snapshot it is sent. The tests ask for "the
// next snapshot", never for a tick: which tick of the interval a client's snapshots fall on is
// the server's choice.
struct delta_session {
    // earlier: another delta client, joined ticks_before_join ticks before this one.
    explicit delta_session(const match::match_config& config, match::connection* earlier = nullptr,
                           uint32_t ticks_before_join = 0)
        : g(config, world::asteroids_preset()) {
        if (earlier != nullptr) REQUIRE(match_test::join(g, *earlier, hello(true)) != 0);
        for (uint32_t k = 0; k < ticks_before_join; ++k) g.tick();
        player = match_test::join(g, link, hello(true));
        REQUIRE(player != 0);
    }

    // Sends an Input carrying `ack` (nothing when nullopt: the client is silent), ticks up to
    // this client's next snapshot and returns it, decoded and checked against the world.
    decoded_snapshot next_snapshot(std::optional<uint32_t> ack) {
        if (ack) REQUIRE(match_test::send_input(g, link, {++sequence, 1.0f, 0.25f, 0, *ack}));
        for (uint32_t k = 0; k <= snapshot_interval && link.snapshots.empty(); ++k) {
            g.tick();
            if (after_tick) after_tick();
        }
        REQUIRE(link.snapshots.size() == 1);
        const protocol::frame_bytes frame = std::move(link.snapshots.front());
        link.snapshots.clear();
        const protocol::snapshot_view s = read_snapshot(frame);
        REQUIRE(s.tick == g.state().tick());
        INFO("snapshot " << s.tick << " against " << s.baseline_tick);
        const float radius = g.config().view_radius;
        return {s.tick, s.baseline_tick, decode_and_check(rx, s, g.state(), welcomed_body(link), radius)};
    }

    recording_client link;
    match::match g;
    std::function<void()> after_tick;  // sees every tick's state, e.g. to check other clients
    uint32_t player = 0;
    protocol::delta::receiver rx{tick_rate};
    uint32_t sequence = 0;
};

}  // namespace fanout_fixture
