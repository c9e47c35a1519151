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
    c.max_players = players;
    c.preset = "asteroids";
    return c;
}

// Every Input handed to the match goes to the client's ledger; each tick the world's applied
// input is compared with the ledger's, and the sequences the ledger consumed are kept.
struct ledgered_run {
    match_sim sim;
    std::vector<input_ledger> ledgers;
    std::vector<std::vector<std::uint32_t>> consumed;  // per client: the sequence consumed at each tick
    std::map<std::uint32_t, std::size_t> client_of_body;
    std::uint64_t inputs_not_as_ruled = 0;
    std::uint64_t acks_not_as_ruled = 0;
    std::uint64_t acks_checked = 0;

    ledgered_run(const match::match_config& config, const sim_options& options)
        : sim(config, *world::preset_by_name("asteroids"), options) {
        ledgers.assign(sim.size(), input_ledger(config.input_buffer));
        consumed.resize(sim.size());
        for (std::size_t i = 0; i < sim.size(); ++i) {
            sim.server(i).on_input = [this, i](const protocol::input_msg& in) {
                ledgers[i].received(in);
            };
            sim.server(i).on_snapshot_ack = [this, i](std::uint32_t ack) {
                ++acks_checked;
                if (ack != ledgers[i].consumed_sequence()) ++acks_not_as_ruled;
            };
        }
        sim.match().on_tick = [this](const match::tick_record& record, std::uint64_t) {
            for (std::size_t i = 0; i < sim.size(); ++i)
                if (const std::uint32_t body = sim.server(i).body_id()) client_of_body[body] = i;
            for (const world::body_input& applied : record.inputs) {
                const auto it = client_of_body.find(applied.body_id.value());
                if (it == client_of_body.end()) continue;
                const world::player_input ruled = ledgers[it->second].consume();
                consumed[it->second].push_back(ledgers[it->second].consumed_sequence());
                if (ruled.thrust != applied.input.thrust || ruled.turn != applied.input.turn ||
                    ruled.buttons != applied.input.buttons)
                    ++inputs_not_as_ruled;
            }
        };
    }

    // Sequences that were never consumed between the first and the last consumed one: each
    // is an input the world never applied (lost, overtaken, or dropped by a full buffer); the
    // largest number when one was consumed after a newer one.
    std::uint64_t gaps(std::size_t i) const {
        std::uint64_t missing = 0;
        std::uint32_t last = 0;
        for (const std::uint32_t s : consumed[i]) {
            if (s == last) continue;  // the same input again: an underrun repeats it, not consumed twice
            if (s < last) return std::numeric_limits<std::uint64_t>::max();  // an older one after a newer one
            if (last != 0) missing += s - last - 1;
            last = s;
        }
        return missing;
    }
};

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
    ledgered_run run(match_config(16), o);
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
    ledgered_run run(match_config(4), o);
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
