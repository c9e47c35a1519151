#pragma once
// What a simulated link does to the traffic in one direction, and the random numbers it draws
// them from. Time is virtual: nanoseconds on a clock the test advances (sim_time), never read
// from the machine, so a run is a pure function of its seed.
#include <algorithm>
#include <cstdint>

#include "server/world/rng.hpp"
#include "server/world/splitmix64.hpp"
#include "simnet/link_stats.hpp"

namespace arena::simnet {

using sim_time = std::uint64_t;  // ns since the simulation began

inline constexpr sim_time ms = 1'000'000;

struct conditions {
    sim_time latency = 0;              // ns, one way
    sim_time jitter = 0;               // ns: each message's delay is latency ± up to this, uniformly
    double loss = 0;                   // [0, 1): chance that one transmission is lost
    double duplicate = 0;              // [0, 1): chance that a message arrives twice (the copy later)
    double reorder = 0;                // [0, 1): chance that a message is held back by up to reorder_delay
    sim_time reorder_delay = 50 * ms;  // ns
    // Streams (and reliable messages): a lost transmission is resent this long after it was
    // sent, the wait doubling at each loss of the same segment, up to max_retransmit_timeout.
    // 200 ms is Linux's minimum RTO, what a 200 ms round trip gives.
    sim_time retransmit_timeout = 200 * ms;
    sim_time max_retransmit_timeout = 3'200 * ms;
    std::uint32_t segment_bytes = 1448;  // a stream's segments: an Ethernet MSS
};

// The draws of one link: splitmix64 seeded per link, so adding a link does not change what
// the others do.
class dice {
public:
    explicit dice(std::uint64_t seed) : rng_(seed) {}
    // True with probability p.
    bool chance(double p) { return p > 0 && unit() < p; }
    // Uniform in [0, 1), 53 bits.
    double unit() { return static_cast<double>(rng_.next_u64() >> 11) * 0x1.0p-53; }
    // Uniform in [0, n], integers.
    sim_time upto(sim_time n) { return n == 0 ? 0 : rng_.next_u64() % (n + 1); }
    // One way's delay: latency ± jitter, never negative.
    sim_time delay(const conditions& c) {
        const sim_time spread = upto(2 * c.jitter);
        return c.latency + spread >= c.jitter ? c.latency + spread - c.jitter : 0;
    }
    // A reliable transmission (a stream's segment, a reliable message) first sent at `now`:
    // when the copy that gets through leaves, each loss resending it after the retransmission
    // timeout, which doubles up to its cap. The losses are counted in `stats`.
    sim_time resent_until_through(const conditions& c, sim_time now, link_stats& stats) {
        sim_time sent_at = now;
        sim_time timeout = c.retransmit_timeout;
        while (chance(c.loss)) {
            ++stats.lost;
            ++stats.retransmissions;
            sent_at += timeout;
            timeout = std::min(2 * timeout, c.max_retransmit_timeout);
        }
        return sent_at;
    }

private:
    world::rng rng_;
};

// A seed per link from the run's seed and the link's number.
inline std::uint64_t link_seed(std::uint64_t seed, std::uint64_t link) {
    return seed ^ (world::splitmix64::gamma * (link + 1));
}

}  // namespace arena::simnet
