#include <catch2/catch.hpp>

#include "server/host/tick_clock.hpp"

using arena::host::tick_clock;

TEST_CASE("the tick clock runs one tick per period and never drifts", "[net][clock]") {
    tick_clock clock(1000, 10);
    clock.start(0);
    uint64_t ticks = 0;
    // Wake-ups at irregular times: the total still follows the wall time exactly.
    for (int64_t t : {300, 999, 1000, 2500, 2999, 4000, 10000}) ticks += clock.advance(t);
    CHECK(ticks == 10);
    CHECK(clock.overruns() == 0);
    CHECK(clock.next_due_ns() == 11000);
}

TEST_CASE("after a stall the clock catches up a bounded number of ticks and counts the rest", "[net][clock]") {
    tick_clock clock(1000, 3);
    clock.start(0);
    CHECK(clock.advance(10500) == 3);
    CHECK(clock.overruns() == 7);
    // The fraction of a tick is kept: the next tick is due half a period later.
    CHECK(clock.next_due_ns() == 11000);
    CHECK(clock.advance(11000) == 1);
}
