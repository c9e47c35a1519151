// The simulated links on their own: each does to the traffic what its conditions say, a
// stream keeps TCP's promises (in order, exactly once, a loss holds back what follows), and
// the same seed gives the same run.
#include <catch2/catch.hpp>
#include <cstdint>
#include <set>
#include <vector>

#include "simnet/datagram_link.hpp"
#include "simnet/stream_link.hpp"

namespace {

using namespace arena::simnet;

std::vector<std::uint8_t> numbered(std::uint32_t n) {
    return {static_cast<std::uint8_t>(n), static_cast<std::uint8_t>(n >> 8), static_cast<std::uint8_t>(n >> 16),
            static_cast<std::uint8_t>(n >> 24)};
}

std::uint32_t number(const std::vector<std::uint8_t>& m) {
    return m[0] | (m[1] << 8) | (m[2] << 16) | (static_cast<std::uint32_t>(m[3]) << 24);
}

struct arrival {
    std::uint32_t number;
    sim_time at;
    bool operator==(const arrival&) const = default;
};

// Sends `count` numbered messages one `spacing` apart and collects them as they arrive,
// asking the link at each of its due times (the way a harness drives it).
template <typename Send>
std::vector<arrival> run_datagrams(datagram_link& link, std::uint32_t count, sim_time spacing, Send send) {
    std::vector<arrival> got;
    std::vector<std::uint8_t> message;
    std::uint32_t next = 0;
    sim_time now = 0;
    while (next < count || link.next_due()) {
        const sim_time send_at = next < count ? next * spacing : UINT64_MAX;
        now = std::min(send_at, link.next_due().value_or(UINT64_MAX));
        while (link.receive(now, message)) got.push_back({number(message), now});
        if (now == send_at) send(link, numbered(next++), now);
    }
    return got;
}

void plain(datagram_link& link, const std::vector<std::uint8_t>& m, sim_time now) {
    link.send(m, now);
}
void reliable(datagram_link& link, const std::vector<std::uint8_t>& m, sim_time now) {
    link.send_reliable(m, now);
}

conditions internet() {
    conditions c;
    c.latency = 100 * ms;
    c.jitter = 20 * ms;
    c.loss = 0.05;
    return c;
}

}  // namespace

TEST_CASE("a perfect datagram link delivers every message once, after the latency, in order", "[simnet]") {
    conditions c;
    c.latency = 30 * ms;
    datagram_link link(c, 1);
    const auto got = run_datagrams(link, 100, 5 * ms, plain);
    REQUIRE(got.size() == 100);
    for (std::uint32_t i = 0; i < 100; ++i) {
        CHECK(got[i].number == i);
        CHECK(got[i].at == i * 5 * ms + 30 * ms);
    }
}

TEST_CASE("a datagram link loses, delays, duplicates and reorders as told", "[simnet]") {
    conditions c = internet();
    c.duplicate = 0.02;
    c.reorder = 0.01;
    datagram_link link(c, 7);
    const std::uint32_t n = 50'000;
    const auto got = run_datagrams(link, n, 16 * ms, plain);
    const link_stats& s = link.stats();
    CHECK(s.sent == n);
    CHECK(s.lost == Approx(0.05 * n).epsilon(0.1));
    CHECK(s.duplicated == Approx(0.02 * (n - s.lost)).epsilon(0.15));
    CHECK(s.held_back == Approx(0.01 * (n - s.lost)).epsilon(0.25));
    CHECK(got.size() == n - s.lost + s.duplicated);
    CHECK(s.delivered == got.size());

    std::set<std::uint32_t> seen;
    std::uint64_t overtaken = 0;
    std::uint32_t highest = 0;
    for (const arrival& a : got) {
        const sim_time sent = a.number * 16 * ms;
        if (seen.insert(a.number).second) {
            // A first copy: latency ± jitter, plus a hold-back for a few.
            CHECK(a.at >= sent + 80 * ms);
            CHECK(a.at <= sent + 120 * ms + c.reorder_delay);
        }
        if (a.number < highest) ++overtaken;
        highest = std::max(highest, a.number);
    }
    CHECK(seen.size() == n - s.lost);
    // ±20 ms of jitter on messages 16 ms apart reorders neighbours now and then.
    CHECK(overtaken > n / 100);
}

TEST_CASE("reliable messages on a lossy datagram link arrive once each, in order", "[simnet]") {
    conditions c = internet();
    c.loss = 0.3;
    datagram_link link(c, 3);
    const auto got = run_datagrams(link, 2000, 16 * ms, reliable);
    REQUIRE(got.size() == 2000);
    sim_time longest = 0;
    for (std::uint32_t i = 0; i < got.size(); ++i) {
        REQUIRE(got[i].number == i);
        longest = std::max(longest, got[i].at - i * 16 * ms);
    }
    CHECK(link.stats().retransmissions == Approx(2000 * 0.3 / 0.7).epsilon(0.15));
    // A message lost twice waits 200 + 400 ms before its third try.
    CHECK(longest >= 600 * ms + 80 * ms);
}

TEST_CASE("a stream delivers every byte once, in order, and a loss holds back what follows", "[simnet]") {
    conditions c;
    c.latency = 100 * ms;  // no jitter: a segment read late was lost or waited for one that was
    c.loss = 0.001;        // sparse, so that each loss's wait can be seen
    c.duplicate = 0.05;
    c.reorder = 0.05;
    c.segment_bytes = 100;
    stream_link link(c, 11);
    std::vector<std::uint8_t> written;
    std::vector<std::uint8_t> read;
    std::uint64_t late = 0;  // bytes read later than latency and a hold-back allow
    for (sim_time now = 0; now < 20'000 * ms; now += ms) {
        if (now < 10'000 * ms) {
            // 250 bytes a millisecond: three segments, the last one short.
            std::vector<std::uint8_t> chunk(250);
            for (std::size_t i = 0; i < chunk.size(); ++i) chunk[i] = static_cast<std::uint8_t>(written.size() + i);
            link.write(chunk, now);
            written.insert(written.end(), chunk.begin(), chunk.end());
        }
        const std::size_t before = read.size();
        link.read(now, read);
        // Byte i was written at (i / 250) ms and would arrive 100 ms later (150 if held back).
        for (std::size_t i = before; i < read.size(); ++i)
            if (now > (i / 250) * ms + 100 * ms + c.reorder_delay) ++late;
    }
    REQUIRE(read == written);
    const link_stats& s = link.stats();
    CHECK(s.sent == 30'000);
    CHECK(s.lost > 10);
    CHECK(s.duplicated > 1000);  // discarded: the bytes above are still exactly once
    // A loss waits 200 ms for its resend, and so does every byte behind it (50 000 bytes at
    // 250 a millisecond): far more bytes come late than the lost segments held.
    CHECK(late > 100 * s.lost * c.segment_bytes);
}

TEST_CASE("a stream's end comes after its last byte", "[simnet]") {
    conditions c = internet();
    stream_link link(c, 5);
    const std::vector<std::uint8_t> bytes(5000, 42);
    link.write(bytes, 0);
    link.close(0);
    link.write(bytes, 0);  // after close: nothing
    std::vector<std::uint8_t> read;
    bool ended = false;
    for (sim_time now = 0; !ended && now < 10'000 * ms; now = link.next_due().value_or(now + ms)) {
        link.read(now, read);
        ended = link.take_end(now);
        if (ended) CHECK(read.size() == bytes.size());
    }
    REQUIRE(ended);
    CHECK_FALSE(link.take_end(20'000 * ms));  // once
    CHECK_FALSE(link.next_due());
}

TEST_CASE("the same seed gives the same run, another seed another", "[simnet]") {
    conditions c = internet();
    c.duplicate = 0.05;
    c.reorder = 0.05;
    datagram_link a(c, 99);
    datagram_link b(c, 99);
    datagram_link other(c, 100);
    const auto run_a = run_datagrams(a, 5000, 10 * ms, plain);
    CHECK(run_a == run_datagrams(b, 5000, 10 * ms, plain));
    CHECK_FALSE(run_a == run_datagrams(other, 5000, 10 * ms, plain));
}
