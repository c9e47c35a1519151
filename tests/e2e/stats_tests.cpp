// Summaries: nearest-rank percentiles, mean, extremes; and the report's pass/fail rule.
#include <catch2/catch.hpp>
#include <vector>

#include "client_sim/metrics.hpp"
#include "client_sim/report.hpp"
#include "client_sim/stats.hpp"

using arena::bots::bot_outcome;
using arena::bots::sample_set;

TEST_CASE("percentiles of 1..100 are nearest-rank values", "[bots][stats]") {
    sample_set s;
    // Added out of order: summarize() sorts.
    for (int i = 100; i >= 1; --i) s.add(i);
    const auto sum = s.summarize();
    CHECK(sum.count == 100);
    CHECK(sum.mean == Approx(50.5));
    CHECK(sum.min == 1);
    CHECK(sum.p50 == 50);
    CHECK(sum.p99 == 99);
    CHECK(sum.max == 100);
}

TEST_CASE("percentiles of few samples pick measured values", "[bots][stats]") {
    sample_set s;
    s.add(3.5);
    auto one = s.summarize();
    CHECK(one.p50 == 3.5f);
    CHECK(one.p99 == 3.5f);
    CHECK(one.max == 3.5f);
    s.add(1.0);
    s.add(2.0);
    auto three = s.summarize();
    CHECK(three.p50 == 2.0f);
    CHECK(three.p99 == 3.5f);
    CHECK(three.mean == Approx(6.5 / 3));
}

TEST_CASE("an empty set summarises to zeros, and clear() empties it", "[bots][stats]") {
    sample_set s;
    auto empty = s.summarize();
    CHECK(empty.count == 0);
    CHECK(empty.p99 == 0);
    s.add(7);
    s.clear();
    CHECK(s.empty());
    CHECK(s.summarize().mean == 0);
}

TEST_CASE("p99 of 1000 samples ignores the top 10", "[bots][stats]") {
    sample_set s;
    for (int i = 0; i < 990; ++i) s.add(1);
    for (int i = 0; i < 10; ++i) s.add(1000);
    const auto sum = s.summarize();
    CHECK(sum.p99 == 1);
    CHECK(sum.max == 1000);
}

TEST_CASE("the run fails only for well-behaved bots that did not join or lost their session", "[bots][stats]") {
    bot_outcome good;
    good.joined = true;
    good.ended = true;
    CHECK_FALSE(good.failed());

    bot_outcome never_joined;
    CHECK(never_joined.failed());

    bot_outcome dropped = good;
    dropped.ended_early = true;
    dropped.reason = "server closed the connection without Reject or Bye";
    CHECK(dropped.failed());

    bot_outcome goodbye = dropped;
    goodbye.server_goodbye = true;  // Bye, or Reject shutting_down: the server ended the match
    CHECK_FALSE(goodbye.failed());

    bot_outcome protocol = good;
    protocol.protocol_error = true;
    CHECK(protocol.failed());

    bot_outcome misbehaving = dropped;
    misbehaving.misbehaving = true;
    misbehaving.joined = false;
    CHECK_FALSE(misbehaving.failed());

    arena::bots::fleet_metrics metrics;
    metrics.prediction_error_m.add(0.001);  // a measured run (see the next test for one without)
    const std::vector<bot_outcome> all{good, goodbye, misbehaving};
    const auto pass = arena::bots::make_report(metrics, all, 1.0);
    CHECK(pass.exit_code == 0);
    CHECK(pass.misbehaving_dropped == 1);
    const std::vector<bot_outcome> some_fail{good, dropped};
    const auto fail = arena::bots::make_report(metrics, some_fail, 1.0);
    CHECK(fail.exit_code == 1);
    CHECK(fail.failures.at(dropped.reason) == 1);
    CHECK(arena::bots::to_json(fail)["exit_code"] == 1);
}

TEST_CASE("a run where bots played but no prediction was measured fails", "[bots][stats]") {
    bot_outcome good;
    good.joined = true;
    good.ended = true;
    bot_outcome misbehaving;
    misbehaving.misbehaving = true;
    misbehaving.joined = true;
    arena::bots::fleet_metrics empty;
    const std::vector<bot_outcome> played{good, misbehaving};
    const auto r = arena::bots::make_report(empty, played, 1.0);
    CHECK(r.exit_code == 1);
    CHECK(r.failed == 0);  // no bot failed: the run did
    CHECK(r.failures.at(arena::bots::no_prediction_samples) == 1);
    CHECK(arena::bots::summary_table(r).find(arena::bots::no_prediction_samples) != std::string::npos);
    // Only misbehaving bots, or nobody joined: nothing was there to measure.
    const std::vector<bot_outcome> only_misbehaving{misbehaving};
    CHECK(arena::bots::make_report(empty, only_misbehaving, 1.0).exit_code == 0);
}
