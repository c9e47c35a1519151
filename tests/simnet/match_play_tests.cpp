// What a match does for its clients, moved here from the process tests (tests/e2e/) where it
// needed no socket: the same assertions, over near-perfect simulated streams in virtual time,
// so they hold whatever the machine's load and take a fraction of the time.
#include <catch2/catch.hpp>
#include <string>

#include "server/world/presets.hpp"
#include "simnet/match_sim.hpp"

namespace {

using namespace arena;
using namespace arena::simnet;
using phase = bots::client_core::phase;

// arena-server's flags in the process tests: 60 Hz ticks, 20 snapshots/s, 64 players,
// asteroids, seed 1.
match::match_config server_flags(float view_radius) {
    match::match_config c;
    c.tick_rate = 60;
    c.snapshot_rate = 20;
    c.admission.max_players = 64;
    c.preset = "asteroids";
    c.seed = 1;
    c.view_radius = view_radius;
    return c;
}

// Loopback: a tenth of a millisecond each way, nothing lost.
conditions loopback() {
    conditions c;
    c.latency = ms / 10;
    return c;
}

// `clients` bots connecting at `connect_rate` a second play `seconds`, then say Bye.
struct played {
    match_sim sim;

    played(const match::match_config& config, std::uint32_t clients, double connect_rate, std::uint64_t seed,
           std::uint32_t seconds, bots::misbehavior fault = bots::misbehavior::none, double fault_share = 0)
        : sim(config, *world::preset_by_name("asteroids"), options(clients, connect_rate, seed, fault, fault_share)) {
        sim.run_ticks(seconds * 60ULL);
        REQUIRE(sim.finish());
        for (std::size_t i = 0; i < sim.size(); ++i) sim.client(i).add_final_figures(sim.shared().metrics());
    }
    static sim_options options(std::uint32_t clients, double connect_rate, std::uint64_t seed, bots::misbehavior fault,
                               double fault_share) {
        sim_options o;
        o.misbehave = fault;
        o.misbehave_share = fault_share;
        o.kind = link_kind::stream;
        o.clients = clients;
        o.up = o.down = loopback();
        o.seed = seed;
        o.behavior = bots::behavior_choice::mixed;
        o.launch_spacing = static_cast<sim_time>(1e9 / connect_rate);
        return o;
    }
    bots::fleet_metrics& m() { return sim.shared().metrics(); }
};

// The per-bot snapshot rate stays at the server's 20/s (tests/e2e's check_snapshot_rate).
void check_snapshot_rate(bots::fleet_metrics& m) {
    const bots::summary rate = m.snapshots_per_s_per_bot.summarize();
    CHECK(rate.min >= 18.0);
    CHECK(rate.max <= 22.0);
    CHECK(rate.p50 == Approx(20.0).margin(0.5));
    CHECK(m.snapshot_gap_ms.summarize().p50 == Approx(50.0).margin(5.0));
}

// 20 clients, a quarter of them misbehaving with `fault`, play 5 s: exactly the misbehaving
// ones are dropped, with `expected` in the reason, while the others keep their session and
// their snapshot rate (tests/e2e's check_misbehaving_share).
void check_misbehaving_share(bots::misbehavior fault, const std::string& expected) {
    played run(server_flags(100), 20, 200, 5, 5, fault, 0.25);  // arena-server's default view radius
    match_sim& sim = run.sim;
    std::uint32_t misbehaving = 0;
    std::uint32_t dropped = 0;
    for (std::size_t i = 0; i < sim.size(); ++i) {
        const bots::bot_outcome& o = sim.client(i).outcome();
        INFO("client " << i << ": " << o.reason);
        CHECK(o.joined);
        CHECK_FALSE(o.failed());
        if (!o.misbehaving) {
            CHECK_FALSE(o.ended_early);
            continue;
        }
        ++misbehaving;
        if (o.ended_early) ++dropped;
        CHECK(o.reason.find(expected) != std::string::npos);
    }
    CHECK(misbehaving == 5);
    CHECK(dropped == 5);
    check_snapshot_rate(run.m());
}

}  // namespace

TEST_CASE("clients sending NaN inputs are dropped while the others keep their snapshot rate", "[simnet][match]") {
    check_misbehaving_share(bots::misbehavior::nan, "bad_input");
}

TEST_CASE("flooding clients are dropped while the others keep their snapshot rate", "[simnet][match]") {
    check_misbehaving_share(bots::misbehavior::flood, "rate_limit");
}

TEST_CASE("clients decode delta snapshots of their view and acknowledge them", "[simnet][match][delta]") {
    played run(server_flags(120), 40, 100, 3, 6);
    match_sim& sim = run.sim;
    bots::fleet_metrics& m = run.m();
    for (std::size_t i = 0; i < sim.size(); ++i) {
        INFO("client " << i << ": " << sim.client(i).outcome().reason);
        CHECK(sim.client(i).outcome().joined);
        CHECK_FALSE(sim.client(i).outcome().failed());
        CHECK_FALSE(sim.client(i).outcome().ended_early);
    }
    check_snapshot_rate(m);
    // Every snapshot a delta, every one decoded: the checksum in each proves the client holds
    // exactly the server's quantised view.
    CHECK(m.snapshots > 40 * 100);
    CHECK(m.delta_snapshots == m.snapshots);
    CHECK(m.delta_errors == 0);
    // The view: the own body always, and fewer than all 80 bodies in a 400 m world seen 120 m
    // around (π·120² is 28 % of its area).
    const bots::summary view = m.bodies_in_view.summarize();
    CHECK(view.min >= 1);
    CHECK(view.mean < 40);
    // At most 4 bytes per body in view, the codec's bytes (each frame adds about 50 bytes of
    // FlatBuffers and length prefix, which bench/README.md counts too).
    CHECK(static_cast<double>(m.delta_payload_bytes) / static_cast<double>(m.delta_bodies) <= 4.0);
    CHECK(static_cast<double>(m.snapshot_bytes) / static_cast<double>(m.view_bodies) < 32.0);
    // Prediction from quantised state (positions within 2 mm, velocities within 16 mm/s):
    // not bit-exact, but the median error stays at the millimetre scale; the tail is
    // collisions the client does not simulate.
    const bots::summary error = m.prediction_error_m.summarize();
    CHECK(error.count > 1000);
    CHECK(error.p50 < 0.01);
    CHECK(error.p99 < 0.5);
    CHECK(error.max < 5.0);
}
