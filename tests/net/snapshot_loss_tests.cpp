// One UDP client's snapshot loss from its acks and the copies it calls for
// (server/net/snapshot_loss.*), over a simulated link: no socket, no clock.
#include <catch2/catch.hpp>
#include <cstdint>
#include <random>

#include "server/net/snapshot_loss.hpp"

using namespace arena::net;

namespace {

// Snapshots every 3 ticks, each sent as many times as the estimator says, each copy lost with
// probability `loss`; the client acknowledges a snapshot when a copy arrives.
struct lossy_link {
    snapshot_loss estimator;
    std::mt19937 rng{42};
    uint32_t tick = 0;
    uint64_t datagrams = 0;
    uint64_t snapshots = 0;
    uint64_t sent_twice = 0;
    uint64_t lost = 0;  // snapshots none of whose copies arrived

    void run(int count, double loss) {
        std::uniform_real_distribution<double> coin(0.0, 1.0);
        for (int i = 0; i < count; ++i) {
            tick += 3;
            const uint32_t copies = estimator.copies();
            estimator.sent(tick);
            bool arrived = false;
            for (uint32_t c = 0; c < copies; ++c) arrived = coin(rng) >= loss || arrived;
            datagrams += copies;
            ++snapshots;
            sent_twice += copies == 2 ? 1 : 0;
            if (arrived) estimator.acked(tick);
            lost += arrived ? 0 : 1;
        }
    }
};

}  // namespace

TEST_CASE("without loss a UDP client gets each snapshot once", "[net][udp]") {
    lossy_link l;
    l.run(2000, 0.0);
    CHECK(l.estimator.copies() == 1);
    CHECK(l.estimator.datagram_loss() < 0.0001);  // from the 1 % it starts at, down to nothing
    CHECK(l.sent_twice == 0);
    CHECK(l.estimator.samples() >= 1990);
}

TEST_CASE("at 5 % loss a UDP client's estimate finds it and a second copy goes, and stays", "[net][udp]") {
    lossy_link l;
    l.run(400, 0.05);
    CHECK(l.estimator.copies() == 2);
    CHECK(l.estimator.datagram_loss() > 0.01);
    const uint64_t twice_before = l.sent_twice;
    l.run(4000, 0.05);
    // Every 600 snapshots the loss is measured again with one copy, until the first loss.
    CHECK(l.sent_twice - twice_before >= 3600);
}

TEST_CASE("at 5 % loss a new UDP client's first lost snapshot brings the second copy", "[net][udp]") {
    // 200 clients of 8 seconds each (160 snapshots, the length of a bench-loss run): fewer than
    // 1 % of their snapshots may be lost, or more than 1 % of the gaps are two intervals long
    // (a snapshot gap p99 of 100 ms). An estimate that starts at zero loses some 3 snapshots per
    // client before its copies come (2 %).
    uint64_t lost = 0;
    uint64_t snapshots = 0;
    for (uint32_t seed = 1; seed <= 200; ++seed) {
        lossy_link l;
        l.rng.seed(seed);
        l.run(160, 0.05);
        lost += l.lost;
        snapshots += l.snapshots;
    }
    INFO(lost << " of " << snapshots << " snapshots lost");
    CHECK(lost * 100 < snapshots);
}

TEST_CASE("a new UDP client's first lost Input brings the second copy before any snapshot is lost", "[net][udp]") {
    snapshot_loss estimator;
    estimator.input_arrived(1);
    estimator.input_arrived(2);
    CHECK(estimator.copies() == 1);
    estimator.input_arrived(4);  // 3 never came
    CHECK(estimator.copies() == 2);
}

TEST_CASE("a lost Input says nothing once a UDP client's snapshots have been measured", "[net][udp]") {
    lossy_link l;
    l.run(200, 0.0);  // 10 s of snapshots, all acknowledged: the estimate has decayed
    uint32_t sequence = 1;
    for (; sequence <= 600; ++sequence) l.estimator.input_arrived(sequence);
    l.estimator.input_arrived(sequence + 1);  // one skipped
    CHECK(l.estimator.copies() == 1);
    // Nor after a first stretch of copies: from then on the acks alone decide.
    snapshot_loss fresh;
    fresh.input_arrived(1);
    fresh.input_arrived(3);
    REQUIRE(fresh.copies() == 2);
    uint32_t tick = 0;
    for (int i = 0; i < 700; ++i) {
        tick += 3;
        fresh.sent(tick);
        fresh.acked(tick);
    }
    REQUIRE(fresh.copies() == 1);
    fresh.input_arrived(10);
    fresh.input_arrived(12);
    CHECK(fresh.copies() == 1);
}

TEST_CASE("when a UDP client's loss ends the second copy stops", "[net][udp]") {
    lossy_link l;
    l.run(1000, 0.05);
    REQUIRE(l.estimator.copies() == 2);
    l.run(1000, 0.0);
    CHECK(l.estimator.copies() == 1);
    const uint64_t twice = l.sent_twice;
    l.run(1000, 0.0);
    CHECK(l.sent_twice == twice);
}

TEST_CASE("below about 1 % loss a UDP snapshot mostly goes once", "[net][udp]") {
    lossy_link l;
    l.run(20000, 0.002);  // 1000 s at 20 Hz
    INFO(l.sent_twice << " of " << l.snapshots << " sent twice");
    CHECK(l.sent_twice * 10 < l.snapshots);  // at most a tenth of them twice
}

TEST_CASE("a UDP client's skipped ack counts the snapshots between as lost, and repeated or late acks count nothing",
          "[net][udp]") {
    snapshot_loss estimator({.copy_above = 0.9, .smoothing = 0.5});
    for (uint32_t t = 3; t <= 12; t += 3) estimator.sent(t);
    estimator.acked(3);  // the first ack only starts the count
    CHECK(estimator.samples() == 0);
    estimator.acked(3);
    estimator.acked(6);
    CHECK(estimator.samples() == 1);
    CHECK(estimator.datagram_loss() == Approx(0.45));  // from the threshold, 0.9: arrived (0.45)
    estimator.acked(12);                               // 9 never acknowledged: lost; 12 arrived
    CHECK(estimator.samples() == 3);
    CHECK(estimator.datagram_loss() == Approx(0.3625));  // lost (0.725), then arrived (0.3625)
    estimator.acked(9);                                  // late: an input overtaken by a newer one
    CHECK(estimator.samples() == 3);
}
