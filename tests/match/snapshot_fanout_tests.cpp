// Delta snapshots end to end without sockets: clients decode with protocol::delta::receiver,
// lose frames, hold back and delay their acknowledgements, and after every snapshot their
// decoded view must equal the view the test computes on its own from the world: the bodies
// view_index.hpp says are in view, found by brute force and quantised.
#include <catch2/catch.hpp>

#include "match/fanout_fixture.hpp"

using namespace fanout_fixture;

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
