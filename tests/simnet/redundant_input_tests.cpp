// Redundant inputs over the simulated datagram network: each Input repeats the inputs the
// server has not acknowledged (Input.earlier), so that a lost or late datagram's input arrives
// with the next one. Checked in virtual time against the rule (input_ledger): every input
// consumed exactly once and in order under loss, reordering and duplicates, and a client cut
// off for 2 s plays on without reconnecting.
#include <catch2/catch.hpp>
#include <limits>
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
    return c;
}

conditions lossy() {
    conditions c;
    c.latency = 50 * ms;
    c.jitter = 20 * ms;
    c.loss = 0.10;
    c.duplicate = 0.05;
    c.reorder = 0.10;
    return c;
}

}  // namespace

TEST_CASE("with redundant inputs over lossy, reordering datagrams every input is consumed once and in order",
          "[simnet][udp]") {
    sim_options o;
    o.kind = link_kind::datagram;
    o.up = lossy();
    o.down = lossy();
    o.seed = 19;
    o.clients = 16;
    checked_run run(match_config(16), o);
    run.sim.run_ticks(1800);  // 30 s of play

    for (std::size_t i = 0; i < run.sim.size(); ++i) {
        INFO("client " << i << ": " << run.sim.client(i).outcome().reason);
        REQUIRE(run.sim.client(i).current() == phase::playing);
    }
    CHECK(run.sim.shared().metrics().rejects.empty());
    CHECK(run.inputs_not_as_ruled == 0);
    CHECK(run.acks_checked > 16 * 1800 / 3 * 8 / 10);
    CHECK(run.acks_not_as_ruled == 0);
    std::uint64_t gaps = 0, recovered = 0, overflows = 0, consumed = 0;
    for (std::size_t i = 0; i < run.sim.size(); ++i) {
        const input_ledger& l = run.ledgers[i];
        CHECK(l.consumed() + l.overflows() + l.waiting() == l.accepted());
        gaps += run.gaps(i);
        recovered += l.recovered();
        overflows += l.overflows();
        consumed += l.consumed();
    }
    INFO("consumed " << consumed << ", recovered from later Inputs " << recovered << ", overflows " << overflows);
    // 10 % loss and 10 % held back by up to 50 ms: thousands of inputs came only inside a later
    // Input, and none is missing (a loss of 9 datagrams in a row would be needed).
    CHECK(recovered > consumed / 20);
    CHECK(recovered == run.sim.match().counters().inputs_recovered);
    CHECK(gaps == 0);
    CHECK(overflows == 0);
    // Snapshots: those duplicated or overtaken were dropped, never applied out of order (the
    // core ends its session on a snapshot older than one it applied, checked above).
    CHECK(run.sim.shared().metrics().stale_messages > 0);
}

TEST_CASE("a UDP client whose every packet is lost for 2 s plays on without reconnecting", "[simnet][udp]") {
    sim_options o;
    o.kind = link_kind::datagram;
    o.up.latency = o.down.latency = 30 * ms;
    o.up.jitter = o.down.jitter = 5 * ms;
    o.seed = 7;
    o.clients = 4;
    checked_run run(match_config(4), o);
    run.sim.run_ticks(300);
    REQUIRE(run.sim.client(0).current() == phase::playing);
    const std::uint32_t player = run.sim.client(0).player_id();
    const std::uint64_t snapshots_before = run.sim.client(0).snapshots();

    run.sim.cut_off(0, 2000 * ms);
    run.sim.run_ticks(120);  // 2 s: nothing gets through
    const std::uint32_t ack_during = run.sim.client(0).last_ack();
    const std::uint64_t snapshots_during = run.sim.client(0).snapshots();
    run.sim.run_ticks(120);  // 2 s more: the link is back

    INFO(run.sim.client(0).outcome().reason);
    REQUIRE(run.sim.client(0).current() == phase::playing);
    CHECK(run.sim.client(0).player_id() == player);
    CHECK(run.sim.match().counters().reconnects == 0);
    CHECK(run.sim.match().player_count() == 4);
    CHECK(run.sim.shared().metrics().rejects.empty());
    // Snapshots and acks flow again: the server consumes the client's inputs.
    CHECK(snapshots_during - snapshots_before < 5);  // only those already in flight
    CHECK(run.sim.client(0).snapshots() > snapshots_during + 30);
    CHECK(run.sim.client(0).last_ack() > ack_during + 100);
    CHECK(run.inputs_not_as_ruled == 0);
    CHECK(run.acks_not_as_ruled == 0);
    // The others never noticed.
    for (std::size_t i = 1; i < 4; ++i) CHECK(run.gaps(i) == 0);
}
