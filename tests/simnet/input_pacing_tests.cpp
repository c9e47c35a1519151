// Input pacing over the simulated datagram network (client_sim/input_pacer.hpp): under loss a
// late input makes the world repeat its predecessor, and every later input of that client then
// waits one tick longer; without pacing the waits add up over a session. Each delta snapshot
// says how many inputs wait beyond the first (Snapshot.extra_inputs_waiting), and a client
// that sees some in two snapshots in a row leaves one tick's input out.
#include <catch2/catch.hpp>

#include "simnet/checked_run.hpp"
#include "simnet/input_ledger.hpp"
#include "simnet/match_sim.hpp"

namespace {

using namespace arena;
using namespace arena::simnet;
using phase = bots::client_core::phase;

struct paced_run {
    bots::summary lag;            // input lag, ticks: inputs sent and not yet consumed, at each snapshot
    bots::summary error;          // prediction error, m
    std::uint64_t left_out = 0;   // inputs the clients left out
    std::uint64_t underruns = 0;  // ticks the world repeated an input
    std::uint64_t gaps = 0;       // inputs never consumed
};

paced_run play(double loss, std::uint32_t ticks) {
    match::match_config c;
    c.tick_rate = 60;
    c.snapshot_rate = 20;
    c.admission.max_players = 16;
    c.preset = "asteroids";
    sim_options o;
    o.kind = link_kind::datagram;
    o.up.latency = o.down.latency = 5 * ms;
    o.up.jitter = o.down.jitter = 1 * ms;
    o.up.loss = o.down.loss = loss;
    o.seed = 23;
    o.clients = 16;
    checked_run run(c, o);
    run.sim.run_ticks(ticks);
    for (std::size_t i = 0; i < run.sim.size(); ++i) {
        INFO("client " << i << ": " << run.sim.client(i).outcome().reason);
        REQUIRE(run.sim.client(i).current() == phase::playing);
    }
    CHECK(run.inputs_not_as_ruled == 0);
    paced_run r;
    auto& m = run.sim.shared().metrics();
    r.lag = m.input_lag_ticks.summarize();
    r.error = m.prediction_error_m.summarize();
    r.left_out = m.inputs_left_out;
    r.underruns = run.sim.match().counters().input_underruns;
    for (std::size_t i = 0; i < run.sim.size(); ++i) r.gaps += run.gaps(i);
    return r;
}

}  // namespace

TEST_CASE("at 5 % loss over datagrams the input lag stays within a tick of the lossless one for a whole minute",
          "[simnet][udp][pacing]") {
    const paced_run clean = play(0.0, 3600);
    const paced_run lossy = play(0.05, 3600);
    INFO("lossless: lag p50 " << clean.lag.p50 << " p99 " << clean.lag.p99 << " max " << clean.lag.max << ", left out "
                              << clean.left_out << ", underruns " << clean.underruns << ", error p99 "
                              << clean.error.p99);
    INFO("5 % loss: lag p50 " << lossy.lag.p50 << " p99 " << lossy.lag.p99 << " max " << lossy.lag.max << ", left out "
                              << lossy.left_out << ", underruns " << lossy.underruns << ", error p99 "
                              << lossy.error.p99);
    CHECK(clean.gaps == 0);
    CHECK(lossy.gaps == 0);
    CHECK(lossy.lag.p99 <= clean.lag.p99 + 1);
    CHECK(lossy.lag.max <= clean.lag.max + 3);  // a burst after three lost in a row, drained at once
    CHECK(clean.left_out == 0);
    CHECK(lossy.left_out > 0);  // the pacing did the draining: without it the p99 is 4
}
