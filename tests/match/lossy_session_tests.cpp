// The long lossy session: clients join and leave, lose frames, hold back and delay their
// acknowledgements, and after every snapshot each decoded view must equal the view the test
// computes on its own from the world.
#include <catch2/catch.hpp>

#include "match/fanout_fixture.hpp"

using namespace fanout_fixture;

namespace {

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
    uint64_t retags = 0;          // kinds the game changed during the session
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

// The game retags a body now and then (a rock becomes another kind): every client holding it
// must get its shape again with the new kind.
void retag_one(match::match& g, world::rng& rng, session_stats& stats) {
    const auto bodies = g.state().bodies();
    const world::body& b = bodies[below(rng, static_cast<uint32_t>(bodies.size()))];
    if (b.is_static()) return;
    g.set_body_kind(b.id, static_cast<uint8_t>(1 + (g.body_kind(b.id) + below(rng, 2)) % 3));
    ++stats.retags;
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
        if (one_in(rng, 10)) retag_one(g, rng, stats);
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
                  << ", bodies checked " << stats.shapes_checked << ", retags " << stats.retags);
    const match::match_counters counters = g.counters();
    // Shapes: described far less often than the bodies they serve, and always held in time.
    CHECK(stats.shapes > 0);
    CHECK(stats.shapes_checked > 10 * stats.shapes);
    CHECK(stats.retags > 300);  // and every decoded view held each retagged body's new kind
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
