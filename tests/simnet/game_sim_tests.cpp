// The game as the clients hear it (protocol/README.md, "Players and game events"), over
// links that lose, duplicate and reorder: every client holds every player's line as the server
// had it at the snapshot the client applied last, takes each event once and in order, follows
// its own ship through respawns, and gets the final scoreboard and the winner in the last Bye.
#include <catch2/catch.hpp>
#include <map>

#include <unistd.h>

#include <cstdio>
#include <optional>

#include "server/replay/recorder.hpp"
#include "server/replay/replayer.hpp"
#include "server/rules/rules.hpp"
#include "server/world/presets.hpp"
#include "simnet/match_sim.hpp"

namespace {

using namespace arena;
using namespace arena::simnet;
using phase = bots::client_core::phase;

conditions lossy(bool datagrams) {
    conditions c;
    c.latency = 80 * ms;
    c.jitter = 20 * ms;
    c.loss = datagrams ? 0.15 : 0.03;
    if (datagrams) {
        c.duplicate = 0.05;
        c.reorder = 0.1;
    }
    return c;
}

// Ten hunter bots on `kind` links, delta snapshots or not.
sim_options hunters(link_kind kind, bool delta, std::uint64_t seed) {
    sim_options o;
    o.kind = kind;
    o.clients = 10;
    o.delta_snapshots = delta;
    o.behavior = bots::behavior_choice::hunter;
    o.seed = seed;
    return o;
}

// The asteroids preset played by the Asteroids rules, for ten players.
match::match_config asteroids_match(float view_radius) {
    match::match_config config;
    config.preset = "asteroids";
    config.admission.max_players = 10;
    config.view_radius = view_radius;
    return config;
}
world::world_config asteroids_rules_world() {
    world::world_config world = *world::preset_by_name("asteroids");
    world.rules = "asteroids";
    return world;
}

}  // namespace

TEST_CASE("every client holds the server's scoreboard lines and hears each event once, over lossy links",
          "[simnet][match][game]") {
    const link_kind kind = GENERATE(link_kind::datagram, link_kind::stream);
    const bool datagrams = kind == link_kind::datagram;
    // Streams: BodyState clients of the whole world share one frame; datagrams: delta views.
    const float view_radius = datagrams ? 100.0f : 0.0f;
    INFO((datagrams ? "datagrams, delta snapshots" : "stream, shared BodyState snapshots"));
    sim_options o = hunters(kind, datagrams, 91);
    o.up = o.down = lossy(datagrams);
    match::match_config config = asteroids_match(view_radius);
    config.admission.max_inputs_per_second = 4u * config.tick_rate;  // a lossy stream's bursts (match_sim_tests.cpp)
    match_sim sim(config, asteroids_rules_world(), o);

    // The server's scoreboard and each player's ship after every tick, to compare with what
    // each client holds as of its newest snapshot.
    std::map<uint32_t, std::vector<rules::score_line>> boards;
    std::map<uint32_t, std::map<uint32_t, uint32_t>> ships;  // tick -> player -> body (0: none)
    for (int t = 0; t < 1800; ++t) {
        sim.run_ticks(1);
        const uint32_t tick = sim.match().state().tick();
        boards[tick] = sim.match().game_rules().scoreboard();
        for (const rules::score_line& line : boards[tick])
            ships[tick][line.player] = sim.match().game_rules().body_of(line.player);
    }
    const match::match_counters counters = sim.match().counters();
    REQUIRE(counters.hits > 0);
    REQUIRE(counters.shots > 0);
    const bots::fleet_metrics& m = sim.shared().metrics();
    CHECK(m.game_events > 0);
    uint64_t respawns_followed = 0;
    for (std::size_t i = 0; i < sim.size(); ++i) {
        const bots::client_core& c = sim.client(i);
        INFO("client " << i << ": " << c.outcome().reason);
        REQUIRE(c.current() == phase::playing);
        const auto board = boards.find(c.last_snapshot_tick());
        REQUIRE(board != boards.end());
        REQUIRE(c.players().size() == board->second.size());
        for (const rules::score_line& line : board->second) {
            INFO("player " << line.player);
            const auto held = c.players().find(line.player);
            REQUIRE(held != c.players().end());
            CHECK(held->second.score == line.score);
            CHECK(held->second.kills == line.kills);
            CHECK(held->second.deaths == line.deaths);
            CHECK(held->second.lives == line.lives);
            CHECK(static_cast<int>(held->second.state) == static_cast<int>(line.state));
            CHECK(held->second.shots <= line.shots);  // shots ride along: never ahead
            CHECK(c.player_name(line.player).rfind("sim-", 0) == 0);
        }
        // Asteroids' manifest: its body tags and keys, no fields beside the protocol's line.
        CHECK(c.manifest() == sim.match().game_rules().manifest());
        CHECK(c.manifest().name == "asteroids");
        CHECK(c.player_values().empty());
        // Each event once, in order; the client's own body follows its respawns.
        uint32_t previous = 0;
        for (const protocol::game_event& e : c.events()) {
            CHECK(e.sequence > previous);
            previous = e.sequence;
            if (e.kind == protocol::GameEventKind::respawn && e.player == c.player_id()) ++respawns_followed;
        }
        if (const uint32_t ship = ships[c.last_snapshot_tick()][c.player_id()]; ship != 0) CHECK(c.entity_id() == ship);
    }
    CHECK(respawns_followed > 0);

    // The end: the Bye carries the rules' winner and the final scoreboard, exact.
    const protocol::match_result result = sim.match().result();
    REQUIRE(result.over);
    sim.match().shut_down("match over (test)");
    sim.run_ticks(300);
    for (std::size_t i = 0; i < sim.size(); ++i) {
        const bots::client_core& c = sim.client(i);
        INFO("client " << i << ": " << c.outcome().reason);
        CHECK(c.ended());
        CHECK(c.result() == result);
        CHECK(c.outcome().final_scoreboard);
        REQUIRE(c.outcome().scoreboard.size() == result.scoreboard.size());
    }
}

TEST_CASE("own shots predicted by the clients spawn exactly as the server's, over a stream without loss",
          "[simnet][match][game][shots]") {
    // Streams at loopback latency, nothing lost: full BodyState snapshots of the whole world,
    // and delta snapshots of a 100 m view.
    const bool delta = GENERATE(false, true);
    INFO((delta ? "delta snapshots, 100 m view" : "BodyState snapshots of the whole world"));
    sim_options o = hunters(link_kind::stream, delta, 17);
    o.up.latency = o.down.latency = ms / 10;
    match_sim sim(asteroids_match(delta ? 100.0f : 0.0f), asteroids_rules_world(), o);
    sim.run_ticks(1800);
    for (std::size_t i = 0; i < sim.size(); ++i) sim.client(i).add_final_figures(sim.shared().metrics());
    bots::fleet_metrics& m = sim.shared().metrics();
    const bots::shot_counts& shots = m.own_shots;
    const std::uint64_t fired = sim.match().counters().shots;
    const std::uint64_t matched = shots.exact + shots.with_error;
    const bots::summary error = m.own_shot_error_m.summarize();
    INFO("own shots: " << shots.exact << " exact, " << shots.with_error << " with error (p99 " << error.p99 << " m), "
                       << shots.unconfirmed << " unconfirmed, " << shots.unpredicted << " unpredicted, of the server's "
                       << fired);
    // Most of the server's shots were predicted: the others came when a bullet of a ship at
    // its cap hit a rock between two snapshots (the client does not simulate rocks), which
    // frees the gun on the server before the client learns of it. Measured: 90 % and 88 %.
    REQUIRE(fired > 300);
    CHECK(matched * 100 >= fired * 80);
    CHECK(shots.unconfirmed * 100 <= fired);
    if (!delta) {
        // The server's floats arrive unchanged: every matched spawn is bit-exact (measured 417 of 417).
        CHECK(shots.exact * 100 >= matched * 99);
    } else {
        // Quantised states (positions within 2 mm, velocities within 16 mm/s) cannot give the
        // same bits; the spawn is then off by the quantisation (measured p99 2.7 mm, max 3.1 mm).
        CHECK(error.p99 < 0.005);
        CHECK(error.max < 0.01);
    }
}

namespace {

// Hit registration (client_sim/hit_registration.hpp) of ten hunters over datagrams of 50 ms
// each way (±10 ms), 1 % lost, the match compensating `lag_compensation_ms`. With `record`, the
// match is recorded there, every tick. With the victims' side: how long before they heard of a
// ship lost to a bullet they had shown themselves where it was hit (hit_after_seen_ms).
struct hit_figures {
    bots::hit_counts hits;
    bots::summary seen_ms;
};

hit_figures hit_registration(std::uint32_t lag_compensation_ms, const std::string& record = {}) {
    sim_options o = hunters(link_kind::datagram, true, 31);
    o.up.latency = o.down.latency = 50 * ms;
    o.up.jitter = o.down.jitter = 10 * ms;
    o.up.loss = o.down.loss = 0.01;
    match::match_config config = asteroids_match(100.0f);
    config.lag_compensation_ms = lag_compensation_ms;
    match_sim sim(config, asteroids_rules_world(), o);
    std::optional<replay::recorder> recorder;
    if (!record.empty()) {
        const match::match& m = sim.match();
        auto opened = replay::recorder::open(
            record, replay::make_header(m.state(), m.config().preset, m.config().seed, m.config().tick_rate, 1));
        REQUIRE(opened.ok());
        recorder.emplace(std::move(opened.value));
        sim.match().on_tick = [&](const match::tick_record& t, uint64_t hash) {
            REQUIRE(recorder->record_tick(t, hash).ok());
        };
    }
    sim.run_ticks(2400);
    CHECK(sim.finish());
    if (recorder) {
        // The state hash (the world's, then the rules'), as every recorded tick's.
        const match::match& m = sim.match();
        REQUIRE(recorder->finish(m.state().tick(), rules::state_hash(m.state(), m.game_rules())).ok());
        sim.match().on_tick = nullptr;
    }
    for (std::size_t i = 0; i < sim.size(); ++i) sim.client(i).add_final_figures(sim.shared().metrics());
    return {sim.shared().metrics().hits, sim.shared().metrics().hit_after_seen_ms.summarize()};
}

double confirmed_share(const bots::hit_counts& h) {
    return h.claimed == 0 ? 0.0 : static_cast<double>(h.confirmed) / static_cast<double>(h.claimed);
}

}  // namespace

TEST_CASE("the server confirms the hits its shooters saw at 100 ms of round trip, with lag compensation",
          "[simnet][match][game][lag]") {
    const std::string path = "/tmp/arena_hit_registration_" + std::to_string(::getpid()) + ".arpl";
    const hit_figures on_figures = hit_registration(250, path);
    const hit_figures off_figures = hit_registration(0);
    const bots::hit_counts& on = on_figures.hits;
    const bots::hit_counts& off = off_figures.hits;
    const auto line = [](const bots::hit_counts& h) {
        return std::to_string(h.claimed) + " claimed, " + std::to_string(100.0 * confirmed_share(h)) +
               " % confirmed, " + std::to_string(h.unclaimed_hits) + " unclaimed server hits, " +
               std::to_string(h.contested) + " unconfirmed claims on targets taken first by another";
    };
    INFO("compensation on (250 ms): " << line(on));
    INFO("compensation off: " << line(off));
    WARN("hit registration at 100 ms round trip: on " << line(on) << "; off " << line(off));
    // Measured (seed 31, 40 s, bots showing an interpolated view: client_sim/shown_view.hpp): on,
    // 229 claimed, 96.9 % confirmed, 7 unclaimed server hits (3.1 %); off, 225 claimed, 88.4 %
    // confirmed, 57 unclaimed (22 %). Hunters mostly shoot rocks, which move little in a round
    // trip; the ships are where compensation matters.
    REQUIRE(on.claimed >= 30);
    REQUIRE(off.claimed >= 30);
    CHECK(confirmed_share(on) >= 0.95);
    CHECK(on.unclaimed_hits * 100 <= (on.confirmed + on.unclaimed_hits) * 5);
    // Without compensation, measurably fewer: the server judges against the present.
    CHECK(confirmed_share(off) + 0.03 <= confirmed_share(on));
    CHECK(off.unclaimed_hits > on.unclaimed_hits);

    // The victims' side: a ship lost to a bullet was shown where it was hit this long before
    // the news came. Without compensation that is the round trip and the client's lead; with
    // it, the shooter's view's age comes on top, never more than the 250 ms cap.
    const bots::summary& seen_on = on_figures.seen_ms;
    const bots::summary& seen_off = off_figures.seen_ms;
    WARN("hit after seen, ms: on p50 " << seen_on.p50 << " p99 " << seen_on.p99 << " max " << seen_on.max << " ("
                                       << seen_on.count << " ships); off p50 " << seen_off.p50 << " p99 "
                                       << seen_off.p99 << " max " << seen_off.max << " (" << seen_off.count << ")");
    REQUIRE(seen_on.count >= 5);
    REQUIRE(seen_off.count >= 5);
    CHECK(seen_off.min >= 50.0);  // at least the news's one way
    CHECK(seen_on.p50 > seen_off.p50);
    CHECK(seen_on.max <= seen_off.max + 250.0 + 1000.0 / 60);

    // The compensated match replays from its recording with every tick's hash equal: each
    // verdict the same (the rewinds are part of the recorded inputs).
    auto replayer = replay::replayer::open(path);
    REQUIRE(replayer.ok());
    const replay::replay_report report = replayer.value->run();
    std::remove(path.c_str());
    INFO(report.error);
    INFO("first mismatch at tick " << (report.mismatch ? report.mismatch->tick : 0) << ", of " << report.ticks_replayed
                                   << " replayed from " << report.start_tick);
    CHECK(report.complete);
    CHECK_FALSE(report.mismatch.has_value());
    CHECK(report.hashes_checked > 2400);
}
