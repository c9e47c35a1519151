// Hit registration's bookkeeping (client_sim/hit_registration.hpp): claims against the server's
// hits within a window of ticks, one claim per bullet, each hit confirming at most one claim.
#include <catch2/catch.hpp>

#include "client_sim/hit_registration.hpp"

using arena::bots::hit_registration;

TEST_CASE("a claim is confirmed by the server's hit on its target within the window", "[bots][hits]") {
    hit_registration h(60);
    h.claim(7, 100, 1000);
    h.server_hit(100, 1012);  // a round trip and the rewind later
    h.advance(2000);
    CHECK(h.counts().claimed == 1);
    CHECK(h.counts().confirmed == 1);
    CHECK(h.counts().unclaimed_hits == 0);
}

TEST_CASE("a hit on another target, or outside the window, confirms nothing and is unclaimed", "[bots][hits]") {
    hit_registration h(60);
    h.claim(7, 100, 1000);
    h.server_hit(101, 1010);  // another target
    h.server_hit(100, 1100);  // too late
    h.advance(2000);
    CHECK(h.counts().claimed == 1);
    CHECK(h.counts().confirmed == 0);
    CHECK(h.counts().unclaimed_hits == 2);
}

TEST_CASE("one claim per bullet, a claimed target is taken, and one hit confirms one claim", "[bots][hits]") {
    hit_registration h(60);
    h.claim(7, 100, 1000);
    h.claim(7, 101, 1001);  // the same bullet again: ignored
    CHECK(h.has_claimed(7));
    CHECK(h.taken(100));
    CHECK_FALSE(h.taken(101));
    h.claim(8, 100, 1002);  // another bullet's claim on the same target (the caller skips taken ones)
    h.server_hit(100, 1010);
    h.advance(2000);
    CHECK(h.counts().claimed == 2);
    CHECK(h.counts().confirmed == 1);
}

TEST_CASE("at the end, claims still inside their window are left out and pending hits are unclaimed", "[bots][hits]") {
    hit_registration h(60);
    h.claim(1, 100, 1000);  // window closed by the end: claimed, not confirmed
    h.claim(2, 200, 1990);  // window still open at the end: left out
    h.server_hit(300, 1995);
    h.finish(2000);
    CHECK(h.counts().claimed == 1);
    CHECK(h.counts().confirmed == 0);
    CHECK(h.counts().unclaimed_hits == 1);
}

TEST_CASE("a hit that arrives before the claim is matched when the claim comes", "[bots][hits]") {
    hit_registration h(60);
    h.server_hit(100, 1000);
    h.claim(3, 100, 1005);
    h.finish(2000);
    CHECK(h.counts().confirmed == 1);
    CHECK(h.counts().unclaimed_hits == 0);
}

TEST_CASE("an unconfirmed claim on a target something else took first is counted contested", "[bots][hits]") {
    hit_registration h(60);
    h.claim(7, 100, 1000);
    h.other_hit(100, 1005);  // another player's bullet got there first
    h.claim(8, 200, 1000);
    h.other_hit(200, 1200);  // long after: not what kept this claim from being confirmed
    h.claim(9, 300, 1000);
    h.other_hit(300, 1010);
    h.server_hit(300, 1012);  // confirmed after all: not contested
    h.advance(2000);
    CHECK(h.counts().claimed == 3);
    CHECK(h.counts().confirmed == 1);
    CHECK(h.counts().contested == 1);
}
