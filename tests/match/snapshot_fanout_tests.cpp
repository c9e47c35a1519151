// Delta snapshots end to end without sockets: clients decode with protocol::delta::receiver,
// lose frames, hold back and delay their acknowledgements, and after every snapshot their
// decoded view must equal the view the test computes on its own from the world: the bodies
// view_index.hpp says are in view, found by brute force and quantised.
#include <catch2/catch.hpp>

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

using namespace arena;
using protocol::delta::quantized_body;

namespace {

constexpr uint16_t tick_rate = 60;
constexpr uint32_t snapshot_interval = 3;  // 60 Hz ticks, 20 Hz snapshots

match::match_config delta_config(float view_radius, uint32_t delta_history = 32) {
    match::match_config c;
    c.tick_rate = tick_rate;
    c.snapshot_rate = tick_rate / snapshot_interval;
    c.view_radius = view_radius;
    c.delta_history = delta_history;
    return c;
}

// Ticks a snapshot stays usable as a baseline: the server keeps the last delta_history.
uint32_t kept_ticks(const match::match_config& c) {
    return c.delta_history * snapshot_interval;
}

protocol::hello_msg hello(bool delta) {
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
uint32_t welcomed_body(const recording_client& c) {
    for (const protocol::frame_bytes& frame : c.control) {
        auto message = protocol::verify_message(frame, protocol::server_frame_limits);
        REQUIRE(message);
        if (auto welcome = protocol::decode_welcome(*message.value)) return welcome.value.entity_id;
    }
    return 0;
}

// A snapshot frame as a client reads it: verified, then decoded in place (it points into frame).
protocol::snapshot_view read_snapshot(const protocol::frame_bytes& frame) {
    auto message = protocol::verify_message(frame, protocol::server_frame_limits);
    REQUIRE(message);
    auto snapshot = protocol::decode_snapshot(*message.value);
    INFO(snapshot.error);
    REQUIRE(snapshot);
    return snapshot.value;
}

protocol::BodyState body_state(const world::body& b) {
    return {b.id, b.owner, b.position.x(), b.position.y(), b.velocity.x(), b.velocity.y(), b.angle, b.angular_velocity};
}

// view_index.hpp's definition by brute force: the own body and every body whose circle comes
// within `radius` of its centre, the shortest way round; every body when radius is 0. The
// test is the index's own float expression, so that bodies on the edge agree.
std::vector<const world::body*> bodies_in_view(const world::world& w, uint32_t own_id, float radius) {
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

std::vector<quantized_body> quantized_view(const world::world& w, uint32_t own_id, float radius) {
    std::vector<quantized_body> view;
    for (const world::body* b : bodies_in_view(w, own_id, radius)) {
        view.push_back(protocol::delta::quantize(body_state(*b)));
    }
    return view;
}

std::vector<uint32_t> ids_of(std::span<const quantized_body> bodies) {
    std::vector<uint32_t> ids;
    for (const quantized_body& b : bodies) ids.push_back(b.id);
    return ids;
}

std::vector<uint32_t> ids_of(std::span<const protocol::BodyState> bodies) {
    std::vector<uint32_t> ids;
    for (const protocol::BodyState& b : bodies) ids.push_back(b.id());
    return ids;
}

std::vector<uint32_t> ids_of(std::span<const world::body* const> bodies) {
    std::vector<uint32_t> ids;
    for (const world::body* b : bodies) ids.push_back(b->id);
    return ids;
}

std::vector<uint32_t> ids_of(std::span<const world::body> bodies) {
    std::vector<uint32_t> ids;
    for (const world::body& b : bodies) ids.push_back(b.id);
    return ids;
}

// A BodyState snapshot (a client without delta_snapshots) holds its view's bodies, floats exact.
void check_full_view(const protocol::snapshot_view& s, const world::world& w, uint32_t own_id, float radius) {
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
std::vector<uint32_t> decode_and_check(protocol::delta::receiver& rx, const protocol::snapshot_view& s,
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

// --- The long random session -------------------------------------------------------------

bool one_in(world::rng& rng, uint64_t n) {
    return rng.next_u64() % n == 0;
}
uint32_t below(world::rng& rng, uint32_t n) {
    return static_cast<uint32_t>(rng.next_u64() % n);
}

constexpr uint32_t max_ack_lag = 24;  // ticks an acknowledgement may take to reach the server

// One connection, its decoder and its network's mood.
struct sim_client {
    std::unique_ptr<recording_client> link = std::make_unique<recording_client>();  // the match keeps its address
    std::string identity;
    uint32_t player = 0;
    uint32_t body = 0;  // from Welcome; 0 before
    bool delta = true;
    protocol::delta::receiver rx{tick_rate};
    uint32_t sequence = 0;
    uint32_t acked = 0;         // the snapshot_ack of the last Input sent: what the server holds
    uint32_t welcomed_at = 0;   // tick of its Welcome
    uint32_t first_tick = 0;    // the first snapshot this connection was sent
    uint32_t last_tick = 0;     // the newest
    uint32_t loss_per_256 = 0;  // chance that a snapshot is lost
    uint32_t burst_until = 0;   // every snapshot before this tick is lost
    uint32_t silent_until = 0;  // no Input at all before this tick
    uint32_t frozen_until = 0;  // before this tick Inputs carry frozen_ack (acks withheld)
    uint32_t frozen_ack = 0;
    uint32_t ack_lag = 0;                             // ticks an ack takes to arrive (late acks)
    std::deque<uint32_t> acks;                        // rx.ack() after each of the last ticks, newest last
    std::map<uint32_t, protocol::shape_desc> shapes;  // what it holds: the newest view's bodies'
};

// A player's place in the session: connected, waiting to reconnect, or empty.
struct slot {
    bool delta = true;
    std::optional<sim_client> client;
    std::string waiting;  // identity of the player whose body waits for its reconnect
    uint32_t reconnect_at = 0;
    std::optional<protocol::delta::receiver> kept_rx;  // a decoder the client kept over the reconnect
};

struct session_stats {
    uint64_t delta_frames = 0;  // sent against a baseline (lost ones included)
    uint64_t keyframes = 0;
    uint64_t keyframes_despite_ack = 0;  // the client's ack was too old or from another connection
    uint64_t older_baselines = 0;        // decoded against a view older than its newest (late ack)
    uint64_t full_frames = 0;
    uint64_t lost = 0;
    uint64_t decoded = 0;
    uint64_t shapes = 0;          // shapes described by the snapshots that arrived
    uint64_t shapes_checked = 0;  // bodies of decoded views whose shape the client held
};

// A client keeps the shapes each snapshot that arrives describes (protocol/README.md,
// "Shapes")...
void take_shapes(sim_client& c, const protocol::snapshot_view& s, session_stats& stats) {
    std::vector<protocol::shape_desc> got;
    const std::string problem = protocol::read_shapes(s.shapes, s.shape_vertices, got);
    INFO(problem);
    REQUIRE(problem.empty());
    for (const protocol::shape_desc& d : got) c.shapes[d.id] = d;
    stats.shapes += got.size();
}

// ... and, once it decoded a view, holds the shape of every body in it (the world's own,
// with the kind the match gave it); it forgets the shapes of bodies that left the view.
void check_shapes(sim_client& c, std::span<const uint32_t> ids, const match::match& g, session_stats& stats) {
    std::erase_if(c.shapes, [&](const auto& kv) { return !std::ranges::binary_search(ids, kv.first); });
    for (const uint32_t id : ids) {
        INFO("body " << id);
        const auto held = c.shapes.find(id);
        REQUIRE(held != c.shapes.end());
        const world::body* b = g.state().find(id);
        REQUIRE(b != nullptr);
        REQUIRE(held->second == match::describe(g.state(), *b, g.body_kind(id)));
        ++stats.shapes_checked;
    }
}

// The baseline the server must pick (snapshot_fanout.hpp): the client's newest ack, when the
// server still keeps that snapshot and sent it on this connection; else none.
uint32_t expected_baseline(const sim_client& c, uint32_t tick, uint32_t kept) {
    const bool usable = c.acked != 0 && c.acked >= c.first_tick && c.acked < tick && tick - c.acked < kept;
    return usable ? c.acked : 0;
}

void connect(slot& s, match::match& g, world::rng& rng, const std::string& identity) {
    sim_client& c = s.client.emplace();
    c.identity = identity;
    c.delta = s.delta;
    c.player = match_test::join(g, *c.link, hello(s.delta), identity);
    REQUIRE(c.player != 0);
    c.loss_per_256 = below(rng, 64);
    if (s.kept_rx) c.rx = *s.kept_rx;
    s.kept_rx.reset();
}

// Players quit, lose their connection and come back, and new ones join.
void churn(std::vector<slot>& slots, match::match& g, world::rng& rng, uint32_t& next_identity) {
    const uint32_t now = g.state().tick();
    for (slot& s : slots) {
        if (s.client && s.client->body != 0) {
            sim_client& c = *s.client;
            if (one_in(rng, 900)) {
                match_test::say_bye(g, *c.link, "quit");
                s.client.reset();
            } else if (one_in(rng, 900)) {
                match_test::drop(g, *c.link);
                s.waiting = c.identity;
                s.reconnect_at = now + 10 + below(rng, 80);
                if (one_in(rng, 2)) s.kept_rx = c.rx;
                s.client.reset();
            }
        } else if (!s.client && !s.waiting.empty()) {
            if (now >= s.reconnect_at) connect(s, g, rng, std::exchange(s.waiting, {}));
        } else if (!s.client && one_in(rng, 40)) {
            connect(s, g, rng, "player-" + std::to_string(next_identity++));
        }
    }
}

void check_delta(sim_client& c, const protocol::snapshot_view& s, const match::match& g, world::rng& rng,
                 session_stats& stats) {
    REQUIRE(s.is_delta);
    if (c.first_tick == 0) c.first_tick = s.tick;
    INFO("acked " << c.acked << ", first snapshot " << c.first_tick << ", decoder's newest " << c.rx.ack());
    REQUIRE(s.baseline_tick == expected_baseline(c, s.tick, kept_ticks(g.config())));
    ++(s.baseline_tick != 0 ? stats.delta_frames : stats.keyframes);
    if (s.baseline_tick == 0 && c.acked != 0) ++stats.keyframes_despite_ack;
    const uint32_t loss_draw = below(rng, 256);
    if (s.tick < c.burst_until || loss_draw < c.loss_per_256) {
        ++stats.lost;
        return;
    }
    if (s.baseline_tick != 0 && s.baseline_tick < c.rx.ack()) ++stats.older_baselines;
    take_shapes(c, s, stats);
    const std::vector<uint32_t> ids = decode_and_check(c.rx, s, g.state(), c.body, g.config().view_radius);
    check_shapes(c, ids, g, stats);
    ++stats.decoded;
}

// What the tick sent this client: from its Welcome on, one snapshot every snapshot_interval
// ticks, the first within one interval (on which tick of it is the server's choice).
void observe(sim_client& c, const match::match& g, world::rng& rng, session_stats& stats) {
    const uint32_t now = g.state().tick();
    if (c.body == 0) {
        c.body = welcomed_body(*c.link);
        c.welcomed_at = now;
    }
    const std::vector<protocol::frame_bytes> frames = std::exchange(c.link->snapshots, {});
    INFO("tick " << now << ", player " << c.player << (c.delta ? " (delta)" : " (BodyState)"));
    if (c.body == 0) REQUIRE(frames.empty());
    if (c.body == 0 || frames.empty()) {
        REQUIRE(now - (c.last_tick != 0 ? c.last_tick : c.welcomed_at) < snapshot_interval);
        return;
    }
    REQUIRE(frames.size() == 1);
    if (c.last_tick != 0) REQUIRE(now - c.last_tick == snapshot_interval);
    c.last_tick = now;
    for (const protocol::frame_bytes& frame : frames) {
        const protocol::snapshot_view s = read_snapshot(frame);
        REQUIRE(s.tick == now);
        if (c.delta) {
            check_delta(c, s, g, rng, stats);
        } else {
            check_full_view(s, g.state(), c.body, g.config().view_radius);
            take_shapes(c, s, stats);
            check_shapes(c, ids_of(s.bodies), g, stats);
            ++stats.full_frames;
        }
    }
}

// The network's mood changes now and then; then an Input goes out, unless the client is silent.
void send_input(sim_client& c, match::match& g, world::rng& rng) {
    const uint32_t now = g.state().tick();
    c.acks.push_back(c.rx.ack());
    if (c.acks.size() > max_ack_lag + 1) c.acks.pop_front();
    if (one_in(rng, 600)) c.burst_until = now + 1 + below(rng, 150);
    if (one_in(rng, 300)) {
        c.frozen_until = now + 1 + below(rng, 120);
        c.frozen_ack = c.acked;
    }
    if (one_in(rng, 100)) c.ack_lag = below(rng, max_ack_lag + 1);
    if (one_in(rng, 300)) c.silent_until = now + 1 + below(rng, 60);
    if (now < c.silent_until) return;

    const size_t lag = std::min<size_t>(c.ack_lag, c.acks.size() - 1);
    protocol::input_msg in;
    in.sequence = ++c.sequence;
    in.thrust = rng.uniform(-1, 1);
    in.turn = rng.uniform(-1, 1);
    in.buttons = one_in(rng, 20) ? protocol::button_impulse : 0;
    in.snapshot_ack = now < c.frozen_until ? c.frozen_ack : c.acks[c.acks.size() - 1 - lag];
    REQUIRE(match_test::send_input(g, *c.link, in));
    c.acked = in.snapshot_ack;
}

}  // namespace

TEST_CASE("every snapshot of a long lossy session decodes to exactly the client's view", "[match][delta]") {
    match::match g(delta_config(80), world::asteroids_preset());
    // The game tags the rocks (kinds travel with the shapes); the ships stay plain bodies.
    for (const world::body& b : g.state().bodies()) g.set_body_kind(b.id, static_cast<uint8_t>(1 + b.id % 3));
    world::rng rng(20261122);
    std::vector<slot> slots(11);
    slots[0].delta = false;  // one client keeps BodyState snapshots
    uint32_t next_identity = 1;
    session_stats stats;

    for (uint32_t t = 0; t < 6000; ++t) {
        churn(slots, g, rng, next_identity);
        g.tick();
        for (slot& s : slots) {
            if (s.client) observe(*s.client, g, rng, stats);
        }
        for (slot& s : slots) {
            if (!s.client) continue;
            if (s.client->link->closed) {  // no room for its body: the match refused it
                s.client.reset();
            } else if (s.client->body != 0) {
                send_input(*s.client, g, rng);
            }
        }
    }

    INFO("delta " << stats.delta_frames << ", keyframes " << stats.keyframes << " (" << stats.keyframes_despite_ack
                  << " despite an ack), older baselines " << stats.older_baselines << ", lost " << stats.lost
                  << ", decoded " << stats.decoded << ", BodyState " << stats.full_frames << ", shapes " << stats.shapes
                  << ", bodies checked " << stats.shapes_checked);
    const match::match_counters counters = g.counters();
    // Shapes: described far less often than the bodies they serve, and always held in time.
    CHECK(stats.shapes > 0);
    CHECK(stats.shapes_checked > 10 * stats.shapes);
    CHECK(counters.snapshots.shapes_sent >= stats.shapes);
    CHECK(counters.snapshots.delta_frames == stats.delta_frames);
    CHECK(counters.snapshots.keyframes == stats.keyframes);
    CHECK(counters.snapshots.full_frames == stats.full_frames);
    // Each path was taken: deltas, keyframes for joins and for acks the server no longer keeps,
    // baselines older than the client's newest, lost frames, reconnects, BodyState views.
    CHECK(stats.delta_frames > stats.keyframes);
    CHECK(stats.keyframes_despite_ack > 0);
    CHECK(stats.older_baselines > 0);
    CHECK(stats.lost > 0);
    CHECK(stats.full_frames > 0);
    CHECK(counters.reconnects > 0);
    CHECK(counters.leaves > 0);
}

TEST_CASE("dropped acknowledgements: deltas against the last one until it leaves the ring, then a full view",
          "[match][delta]") {
    const match::match_config config = delta_config(80);
    delta_session s(config);
    const uint32_t acked = s.next_snapshot(std::nullopt).tick;
    // Every later ack is dropped: the server still holds `acked`.
    decoded_snapshot d = s.next_snapshot(acked);
    for (; d.tick - acked < kept_ticks(config); d = s.next_snapshot(acked)) CHECK(d.baseline_tick == acked);
    CHECK(d.tick == acked + kept_ticks(config));
    CHECK(d.baseline_tick == 0);
    CHECK(s.next_snapshot(acked).baseline_tick == 0);
    // An ack gets through again: deltas resume against it.
    const uint32_t newest = s.rx.ack();
    CHECK(s.next_snapshot(newest).baseline_tick == newest);
    const match::fanout_counters counters = s.g.counters().snapshots;
    CHECK(counters.delta_frames == config.delta_history);  // 31 against `acked`, 1 against `newest`
    CHECK(counters.keyframes == 3);
}

TEST_CASE("an ack of a snapshot the server no longer keeps, or never sent, gets a full view", "[match][delta]") {
    const match::match_config config = delta_config(80, 4);
    SECTION("too old") {
        delta_session s(config);
        std::vector<uint32_t> ticks;
        for (int k = 0; k < 5; ++k) ticks.push_back(s.next_snapshot(std::nullopt).tick);  // decoded, acks held back
        // Each ack is judged at the next frame: ticks[0] is then 5 snapshots old, ticks[2]
        // exactly 4 (just gone from the ring), ticks[4] 3 (still kept).
        CHECK(s.next_snapshot(ticks[0]).baseline_tick == 0);
        CHECK(s.next_snapshot(ticks[2]).baseline_tick == 0);
        CHECK(s.next_snapshot(ticks[4]).baseline_tick == ticks[4]);
    }
    SECTION("never sent to this client") {
        recording_client other;
        delta_session s(config, &other, 2 * snapshot_interval);
        REQUIRE_FALSE(other.snapshots.empty());
        const uint32_t others = read_snapshot(other.snapshots.back()).tick;
        const uint32_t first = s.next_snapshot(std::nullopt).tick;
        REQUIRE(others < first);
        REQUIRE(first + snapshot_interval - others < kept_ticks(config));  // not too old at the next frame
        CHECK(s.next_snapshot(others).baseline_tick == 0);                 // still kept, but another client's
        const uint32_t now = s.g.state().tick();
        CHECK(s.next_snapshot(now + snapshot_interval).baseline_tick == 0);  // the very tick being encoded
        CHECK(s.next_snapshot(now + 1000).baseline_tick == 0);               // the future
        // The ticks next to this client's newest: not its snapshots (maybe the other client's).
        CHECK(s.next_snapshot(s.rx.ack() + 1).baseline_tick == 0);
        CHECK(s.next_snapshot(s.rx.ack() - 1).baseline_tick == 0);
        CHECK(s.g.counters().snapshots.delta_frames == 0);
        const uint32_t newest = s.rx.ack();
        CHECK(s.next_snapshot(newest).baseline_tick == newest);
    }
}

TEST_CASE("a client that never acknowledges gets a full view every time", "[match][delta]") {
    delta_session s(delta_config(80));
    for (int k = 0; k < 40; ++k) {
        // Inputs with ack 0 and no Inputs at all, alternately.
        const decoded_snapshot d = s.next_snapshot(k % 2 == 0 ? std::optional<uint32_t>(0) : std::nullopt);
        CHECK(d.baseline_tick == 0);
        CHECK(!d.ids.empty());  // the own body at least
    }
    const match::fanout_counters counters = s.g.counters().snapshots;
    CHECK(counters.delta_frames == 0);
    CHECK(counters.keyframes == 40);
}

TEST_CASE("with view radius 0 every client's view is the whole world", "[match][delta]") {
    const size_t everything = world::asteroids_preset().rocks.count + 2;  // the rocks and both ships
    delta_session s(delta_config(0));
    recording_client plain;  // without delta_snapshots: the shared BodyState frame
    REQUIRE(match_test::join(s.g, plain, hello(false)) != 0);
    uint64_t plain_frames = 0;
    s.after_tick = [&] {
        for (const protocol::frame_bytes& frame : std::exchange(plain.snapshots, {})) {
            const protocol::snapshot_view full = read_snapshot(frame);
            CHECK(full.tick == s.g.state().tick());
            check_full_view(full, s.g.state(), welcomed_body(plain), 0);
            CHECK(full.bodies.size() == everything);
            ++plain_frames;
        }
    };
    uint32_t ack = 0;
    for (int k = 0; k < 10; ++k) {
        const decoded_snapshot d = s.next_snapshot(ack);
        CHECK(d.baseline_tick == ack);
        CHECK(d.ids == ids_of(s.g.state().bodies()));
        CHECK(d.ids.size() == everything);
        ack = s.rx.ack();
    }
    CHECK(plain_frames >= 9);
    CHECK(s.g.counters().snapshots.delta_frames == 9);
    CHECK(s.g.counters().snapshots.full_frames == plain_frames);
}
