// A match and its clients over the simulated network, in virtual time: 64 clients for 6000
// ticks (100 s of play) at 100 ms ± 20 ms one way and 5 % loss in each direction, over a stream
// and over datagrams, with every property the protocol promises checked as it happens.
#include <catch2/catch.hpp>
#include <map>
#include <vector>

#include "server/world/presets.hpp"
#include "simnet/checked_run.hpp"
#include "simnet/input_ledger.hpp"
#include "simnet/match_sim.hpp"

namespace {

using namespace arena;
using namespace arena::simnet;
using phase = bots::client_core::phase;

match::match_config match_config(std::uint32_t players) {
    match::match_config c;
    c.tick_rate = 60;
    c.snapshot_rate = 20;
    c.admission.max_players = players;
    c.preset = "asteroids";
    // The default limit (2 × tick rate + 10 inputs a second, counted by arrival) refuses a
    // well-behaved client on a lossy stream: one segment lost three times stalls the stream
    // for 1.4 s (200 + 400 + 800 ms of retransmission timeouts), and its 84 inputs then arrive
    // at once on top of the second's own. Seen here about once a run at 5 % loss; a limit
    // that allows a stall's burst keeps this test about the network.
    c.admission.max_inputs_per_second = 4u * c.tick_rate;
    return c;
}

conditions internet() {
    conditions c;
    c.latency = 100 * ms;
    c.jitter = 20 * ms;
    c.loss = 0.05;
    return c;
}

void check_run(checked_run& run, link_kind kind, std::uint64_t ticks) {
    match_sim& sim = run.sim;
    const bots::fleet_metrics& m = sim.shared().metrics();
    INFO((kind == link_kind::stream ? "stream" : "datagrams"));

    // Every client joined and is still playing: no frame failed verification, no Reject, no
    // ack that went back or acknowledged an input never sent (each ends a client's session).
    for (std::size_t i = 0; i < sim.size(); ++i) {
        INFO("client " << i << ": " << sim.client(i).outcome().reason);
        REQUIRE(sim.client(i).current() == phase::playing);
    }
    CHECK(m.rejects.empty());

    // Every delta a client received decoded.
    CHECK(m.delta_snapshots > sim.size() * ticks / 3 * 8 / 10);
    CHECK(m.delta_errors == 0);

    // Every body of every view a client decoded had its shape at that moment.
    CHECK(m.shapes_received > 0);
    CHECK(m.bodies_without_shape == 0);

    // Inputs: the world applied, tick by tick, exactly the input the rule says (each consumed
    // once, in order), and every snapshot acknowledged the input consumed last.
    CHECK(run.inputs_applied > sim.size() * (ticks - 120));
    CHECK(run.inputs_not_as_ruled == 0);
    CHECK(run.acks_checked > sim.size() * ticks / 3 * 9 / 10);
    CHECK(run.acks_not_as_ruled == 0);
    const match::match_counters counters = sim.match().counters();
    std::uint64_t overflows = 0, underruns = 0, stale = 0;
    for (std::size_t i = 0; i < sim.size(); ++i) {
        const input_ledger& l = run.ledgers[i];
        overflows += l.overflows();
        underruns += l.underruns();
        stale += l.stale();
        // Each input the match accepted was consumed once, dropped by a full buffer, or waits.
        CHECK(l.consumed() + l.overflows() + l.waiting() == l.accepted());
    }
    CHECK(overflows == counters.input_overflows);
    CHECK(underruns == counters.input_underruns);
    CHECK(stale == counters.stale_inputs);
    if (kind == link_kind::stream) {
        // A stream hands the match every input once, in order: none stale, none missing.
        CHECK(run.arrivals_out_of_order == 0);
        CHECK(stale == 0);
        for (const input_ledger& l : run.ledgers) CHECK(l.accepted() == l.last_received());
    }

    // Prediction reconciles: each snapshot drops the inputs it acknowledges and replays the
    // rest, so what stays pending is exactly what the server has not consumed yet.
    for (std::size_t i = 0; i < sim.size(); ++i) {
        const bots::predictor& p = *sim.client(i).prediction();
        CHECK(p.unacknowledged() == p.last_sequence() - sim.client(i).last_ack());
        CHECK(p.dropped_inputs() == 0);
    }
    auto errors = sim.shared().metrics().prediction_error_m;
    const bots::summary e = errors.summarize();
    // Shown with a failure. Measured (seed 2024): over the stream p50 0.17 m, p99 6.6 m, max
    // 32 m, with 87 000 inputs dropped from full buffers after retransmission stalls; over
    // datagrams p50 0.057 m, p99 1.5 m, max 9.4 m, with 61 000 inputs stale (overtaken by a
    // later one: ±20 ms of jitter on inputs 16.7 ms apart), of 384 000 sent.
    INFO("prediction error m: p50 " << e.p50 << " p99 " << e.p99 << " max " << e.max << "; overflows " << overflows
                                    << " underruns " << underruns << " stale " << stale);
    CHECK(e.count > sim.size() * ticks / 3 * 8 / 10);
    CHECK(e.p50 < 0.5);

    // Every session ends in order: each client says Bye, both ends close.
    REQUIRE(sim.finish());
    for (std::size_t i = 0; i < sim.size(); ++i) {
        INFO("client " << i);
        CHECK(sim.client(i).outcome().reason == "run finished");
        CHECK_FALSE(sim.client(i).outcome().failed());
        CHECK(sim.server(i).close_reason() == "client said bye: run finished");
    }
    CHECK(sim.match().player_count() == 0);
}

void play_64_clients(link_kind kind) {
    sim_options o;
    o.kind = kind;
    o.clients = 64;
    o.up = internet();
    o.down = internet();
    o.seed = 2024;
    checked_run run(match_config(64), o);
    run.sim.run_ticks(6000);
    check_run(run, kind, 6000);
}

// A few clients for a few seconds: what a run leaves behind, to compare two runs.
struct fingerprint {
    std::uint64_t world_hash = 0;
    std::vector<std::uint32_t> acks;
    std::vector<std::uint64_t> snapshots;
    std::uint64_t delivered = 0;
    bool operator==(const fingerprint&) const = default;
};

fingerprint short_run(link_kind kind, std::uint64_t seed) {
    sim_options o;
    o.kind = kind;
    o.clients = 8;
    o.up = internet();
    o.down = internet();
    o.up.duplicate = o.down.duplicate = 0.02;
    o.up.reorder = o.down.reorder = 0.02;
    o.seed = seed;
    match_sim sim(match_config(8), *world::preset_by_name("asteroids"), o);
    sim.run_ticks(600);
    fingerprint f;
    f.world_hash = sim.match().state().hash();
    for (std::size_t i = 0; i < sim.size(); ++i) {
        f.acks.push_back(sim.client(i).last_ack());
        f.snapshots.push_back(sim.client(i).snapshots());
        f.delivered += sim.up(i).stats().delivered + sim.down(i).stats().delivered;
    }
    return f;
}

}  // namespace

TEST_CASE("64 clients play 6000 ticks over a stream at 100 ms ± 20 ms and 5 % loss each way", "[simnet][match]") {
    play_64_clients(link_kind::stream);
}

TEST_CASE("64 clients play 6000 ticks over datagrams at 100 ms ± 20 ms and 5 % loss each way", "[simnet][match]") {
    play_64_clients(link_kind::datagram);
}

TEST_CASE("every body a client sees has its shape, with views coming and going over lossy, reordering links",
          "[simnet][match][shapes]") {
    // A small view radius: bodies enter and leave the views all the time, and each entry needs
    // its shape to arrive, over datagrams that lose, duplicate and reorder (shapes confirmed by
    // acks) and over a stream to clients of full BodyState snapshots (described once).
    const link_kind kind = GENERATE(link_kind::datagram, link_kind::stream);
    const bool delta = kind == link_kind::datagram;
    INFO((delta ? "datagrams, delta snapshots" : "stream, BodyState snapshots"));
    sim_options o;
    o.kind = kind;
    o.clients = 12;
    o.up = o.down = internet();
    if (delta) {
        o.up.loss = o.down.loss = 0.15;
        o.up.duplicate = o.down.duplicate = 0.05;
        o.up.reorder = o.down.reorder = 0.1;
    }
    o.delta_snapshots = delta;
    o.seed = 77;
    match::match_config config = match_config(12);
    config.view_radius = 60;
    match_sim sim(config, *world::preset_by_name("asteroids"), o);
    sim.run_ticks(1800);
    const bots::fleet_metrics& m = sim.shared().metrics();
    for (std::size_t i = 0; i < sim.size(); ++i) {
        INFO("client " << i << ": " << sim.client(i).outcome().reason);
        REQUIRE(sim.client(i).current() == phase::playing);
    }
    const match::match_counters counters = sim.match().counters();
    INFO("shapes received " << m.shapes_received << " (" << m.shape_bytes << " bytes), sent "
                            << counters.snapshots.shapes_sent << ", bodies in views " << m.view_bodies);
    CHECK(m.view_bodies > 5 * m.shapes_received);  // each shape serves many snapshots
    CHECK(m.shapes_received > 10 * o.clients);     // and views changed: many more than the first ones
    CHECK(m.bodies_without_shape == 0);
    if (delta) {
        CHECK(m.stale_messages > 0);                                // reordering happened
        CHECK(counters.snapshots.shapes_sent > m.shapes_received);  // some were lost and sent again
    } else {
        CHECK(counters.snapshots.shapes_sent >= m.shapes_received);  // the rest still in flight
    }
}

TEST_CASE("the same seed plays the same match, another seed another", "[simnet][match][determinism]") {
    const link_kind kind = GENERATE(link_kind::stream, link_kind::datagram);
    const fingerprint a = short_run(kind, 5);
    CHECK(a.delivered > 0);
    CHECK(a == short_run(kind, 5));
    CHECK_FALSE(a == short_run(kind, 6));
}
