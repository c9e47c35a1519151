// arena-server and arena-bots as real processes on loopback. Each test starts its own
// server on a free port (--port 0), runs the bots against it and reads their --json report.
#include <signal.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "process.hpp"

namespace {

using arena::test::child_process;
using arena::test::temp_dir;
using namespace std::chrono_literals;
using nlohmann::json;

const std::string bin_dir = ARENA_BIN_DIR;

// A server for one test, stopped (SIGTERM, then SIGKILL by child_process) when it goes.
struct server {
    child_process process;
    unsigned port = 0;

    server(const temp_dir& dir, const std::vector<std::string>& extra = {})
        : process(bin_dir + "/arena-server", args(extra), dir.file("server.log")) {
        const auto p = arena::test::wait_for_listening(process, 5s);
        if (!p) FAIL("arena-server did not print 'listening on': " << process.output());
        port = *p;
    }
    ~server() {
        process.signal(SIGTERM);
        process.wait_for(3s);
    }
    static std::vector<std::string> args(const std::vector<std::string>& extra) {
        std::vector<std::string> a{"--bind",       "127.0.0.1", "--port",   "0",         "--tick-rate",
                                   "60",           "--snapshot-rate", "20", "--max-players", "64",
                                   "--preset",     "asteroids", "--seed",   "1",         "--duration",
                                   "30"};
        a.insert(a.end(), extra.begin(), extra.end());
        return a;
    }
};

struct bots_run {
    int exit_code = -1;
    json report;
    std::string output;
};

bots_run run_bots(const temp_dir& dir, unsigned port, std::vector<std::string> args) {
    const std::string report_file = dir.file("bots.json");
    args.insert(args.end(), {"--host", "127.0.0.1", "--port", std::to_string(port), "--json", report_file});
    child_process bots(bin_dir + "/arena-bots", args, dir.file("bots.log"));
    bots_run r;
    const auto code = bots.wait_for(30s);
    r.output = bots.output();
    INFO(r.output);
    REQUIRE(code.has_value());
    r.exit_code = *code;
    const std::string text = arena::test::read_file(report_file);
    if (!text.empty()) r.report = json::parse(text);
    return r;
}

double figure(const json& report, const std::string& name, const std::string& stat) {
    return report.at("figures").at(name).at(stat).get<double>();
}

// The per-bot snapshot rate of the well-behaved bots stays at the server's 20/s: no bot
// below 18/s (a lost snapshot in 5 s would show as 19.8/s) and none above 22/s.
void check_snapshot_rate(const json& report) {
    CHECK(figure(report, "snapshots_per_s_per_bot", "min") >= 18.0);
    CHECK(figure(report, "snapshots_per_s_per_bot", "max") <= 22.0);
    CHECK(figure(report, "snapshots_per_s_per_bot", "p50") == Approx(20.0).margin(0.5));
    CHECK(figure(report, "snapshot_gap_ms", "p50") == Approx(50.0).margin(5.0));
}

// Runs `bots` bots with a misbehaving share against a fresh server and checks that exactly
// the misbehaving ones were dropped, with `expected` in the reason, while the others kept
// their session and their snapshot rate.
void check_misbehaving_share(const std::string& mode, const std::string& expected,
                             const std::vector<std::string>& server_extra = {}) {
    temp_dir dir;
    server s(dir, server_extra);
    const bots_run r = run_bots(dir, s.port,
                                {"--bots", "20", "--duration", "5", "--behavior", "mixed", "--seed", "5",
                                 "--connect-rate", "200", "--misbehave", mode, "--misbehave-share", "0.25", "--quiet"});
    INFO(r.output);
    CHECK(r.exit_code == 0);
    const json& j = r.report;
    CHECK(j.at("joined") == 20);
    CHECK(j.at("failed") == 0);
    CHECK(j.at("ended_early") == 0);
    CHECK(j.at("misbehaving") == 5);
    CHECK(j.at("misbehaving_dropped") == 5);
    for (const auto& [reason, count] : j.at("misbehaving_drops").items()) {
        INFO(reason);
        CHECK(reason.find(expected) != std::string::npos);
    }
    check_snapshot_rate(j);
}

}  // namespace

TEST_CASE("bots join, get snapshots at the snapshot rate and predict their own body", "[e2e]") {
    temp_dir dir;
    server s(dir);
    const bots_run r = run_bots(dir, s.port,
                                {"--bots", "40", "--duration", "6", "--behavior", "mixed", "--seed", "3",
                                 "--connect-rate", "100"});
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const json& j = r.report;
    CHECK(j.at("joined") == 40);
    CHECK(j.at("failed") == 0);
    CHECK(j.at("ended_early") == 0);
    CHECK(j.at("disconnects").empty());
    check_snapshot_rate(j);
    CHECK(figure(j, "rtt_ms", "count") > 100);
    CHECK(figure(j, "rtt_ms", "p99") < 50.0);  // loopback; generous for a busy 2-core machine
    // A progress line a second.
    CHECK(r.output.find("t=2s bots=40/40 snapshots/s=") != std::string::npos);

    // Prediction error, m. The local world runs the server's code on our body alone, and the
    // wire carries the world's floats unchanged, so a prediction is bit-exact unless the
    // server did something the bot could not know in the few ticks between the snapshot it
    // predicted from and the tick it predicted:
    //  - most of the time nothing: the median is exactly 0;
    //  - a timing slip (an input arriving just after the server's tick, so the server repeats
    //    the previous one): one tick of motion, at most top speed × Δt ≈ 31 m/s / 60 ≈ 0.5 m;
    //  - a collision with a rock or another ship (seek bots chase other bodies): the bot
    //    predicts no bounce. Relative speed ≤ about 40 m/s, restitution ≤ 0.8, a window of at
    //    most 4 ticks: ≤ 1.8 × 40 m/s × 4/60 s ≈ 5 m.
    // Measured (40 bots, 6 s): p50 0, p99 below 0.5 m, max about 1 m.
    CHECK(figure(j, "prediction_error_m", "count") > 1000);
    CHECK(figure(j, "prediction_error_m", "p50") == 0.0);
    CHECK(figure(j, "prediction_error_m", "p99") < 0.5);
    CHECK(figure(j, "prediction_error_m", "max") < 5.0);
}

TEST_CASE("bots sending garbage are dropped; the others keep their snapshot rate", "[e2e]") {
    check_misbehaving_share("garbage", "bad_request");
}

TEST_CASE("bots sending NaN inputs are dropped; the others keep their snapshot rate", "[e2e]") {
    check_misbehaving_share("nan", "bad_input");
}

TEST_CASE("bots with an oversize frame are dropped; the others keep their snapshot rate", "[e2e]") {
    check_misbehaving_share("oversize", "too_large");
}

TEST_CASE("flooding bots are dropped; the others keep their snapshot rate", "[e2e]") {
    check_misbehaving_share("flood", "rate_limit");
}

TEST_CASE("bots closing mid-frame leave; the others keep their snapshot rate", "[e2e]") {
    check_misbehaving_share("abrupt-close", "closed mid-frame");
}

TEST_CASE("slow readers do not slow the others down", "[e2e]") {
    // Not asserted: that the slow readers get dropped. The server drops a client whose writes
    // make no progress for --stall-timeout, but its kernel send buffer (about 4 MB on
    // loopback) takes minutes to fill at one small snapshot every 50 ms.
    temp_dir dir;
    server s(dir, {"--stall-timeout", "1"});
    const bots_run r = run_bots(dir, s.port,
                                {"--bots", "20", "--duration", "5", "--seed", "8", "--misbehave", "slow-reader",
                                 "--misbehave-share", "0.25", "--quiet"});
    CHECK(r.exit_code == 0);
    CHECK(r.report.at("misbehaving") == 5);
    CHECK(r.report.at("ended_early") == 0);
    check_snapshot_rate(r.report);
}

TEST_CASE("bots fail with exit code 1 when no server answers", "[e2e]") {
    temp_dir dir;
    unsigned port = 0;
    {
        server s(dir);  // a port that was just free, now closed again
        port = s.port;
    }
    const bots_run r = run_bots(dir, port, {"--bots", "3", "--duration", "1", "--quiet"});
    CHECK(r.exit_code == 1);
    CHECK(r.report.at("joined") == 0);
    CHECK(r.report.at("failed") == 3);
}

TEST_CASE("arena-bots exits with 2 on a usage error", "[bots][cli]") {
    temp_dir dir;
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"--behavior", "dance"}, {"--bots", "0"}, {"--misbehave", "rude"},
          {"--misbehave-share", "2"}, {"--no-such-flag"}}) {
        child_process bots(bin_dir + "/arena-bots", args, dir.file("usage.log"));
        const auto code = bots.wait_for(5s);
        REQUIRE(code.has_value());
        CHECK(*code == 2);
    }
}
