// What the UDP transport logs of refused datagrams (server/net/udp_refusal_log.*): one line per
// reason per interval, with the count of those not logged, in virtual time.
#include <catch2/catch.hpp>
#include <string>

#include "server/net/udp_refusal_log.hpp"

using namespace arena::net;

namespace {
constexpr int64_t second = 1'000'000'000;
}

TEST_CASE("the first refusal of a reason is logged at once, with its address and why", "[net][udp]") {
    udp_refusal_log log(10 * second);
    auto line = log.refused(udp_refusal::rate, "10.0.0.7", 5 * second);
    REQUIRE(line);
    CHECK(*line == "udp: refused a datagram from 10.0.0.7: over its address's connect rate");
}

TEST_CASE("a flood logs one line per interval, and the next says how many went unlogged", "[net][udp]") {
    udp_refusal_log log(10 * second);
    int lines = 0;
    // 1,000 refusals a second for 25 s: lines at 0 s, 10 s and 20 s.
    std::string last;
    for (int64_t ms = 0; ms < 25'000; ++ms) {
        if (auto line = log.refused(udp_refusal::shape, "10.0.0.1", ms * 1'000'000)) {
            ++lines;
            last = *line;
        }
    }
    CHECK(lines == 3);
    CHECK(last ==
          "udp: refused a datagram from 10.0.0.1: not an ENet connect, or one too short to answer (and 9999 more "
          "for that reason since the last such line)");
}

TEST_CASE("each reason has its own interval", "[net][udp]") {
    udp_refusal_log log(10 * second);
    CHECK(log.refused(udp_refusal::rate, "10.0.0.1", 0));
    CHECK_FALSE(log.refused(udp_refusal::rate, "10.0.0.1", second));
    // A different reason inside the rate's interval is still logged.
    auto line = log.refused(udp_refusal::peer_limit, "10.0.0.2", 2 * second);
    REQUIRE(line);
    CHECK(*line == "udp: refused a datagram from 10.0.0.2: every peer slot is taken");
    CHECK(udp_refusal_key(udp_refusal::peer_limit) == "peer_limit");
    CHECK(udp_refusal_key(udp_refusal::shape) == "shape");
    CHECK(udp_refusal_key(udp_refusal::rate) == "rate");
}
