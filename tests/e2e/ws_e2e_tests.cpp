// arena-bots --transport ws against arena-server --http-port, as real processes on loopback:
// WebSocket and TCP players in the same match, and a misbehaving WebSocket bot dropped alone.
#include <signal.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "process.hpp"
#include "servers.hpp"

namespace {

using arena::test::child_process;
using arena::test::figure;
using arena::test::temp_dir;
using namespace std::chrono_literals;
using nlohmann::json;

const std::string bin_dir = ARENA_BIN_DIR;

// arena-server with --http-port beside TCP.
struct ws_server : arena::test::server_beside_tcp {
    explicit ws_server(const temp_dir& dir)
        : server_beside_tcp(bin_dir, dir, "--http-port", "http listening on"), http_port(second_port) {}
    const unsigned http_port;
};

json run_bots(const temp_dir& dir, const std::string& name, unsigned port, std::vector<std::string> args,
              int expected_exit = 0) {
    const std::string report_file = dir.file(name + ".json");
    args.insert(args.end(), {"--host", "127.0.0.1", "--port", std::to_string(port), "--json", report_file, "--quiet",
                             "--name-prefix", name});
    child_process p(bin_dir + "/arena-bots", args, dir.file(name + ".log"));
    const auto code = p.wait_for(30s);
    INFO(p.output());
    REQUIRE(code.has_value());
    CHECK(*code == expected_exit);
    const std::string text = arena::test::read_file(report_file);
    REQUIRE(!text.empty());
    return json::parse(text);
}

}  // namespace

TEST_CASE("WebSocket bots play a short match beside TCP bots at the snapshot rate", "[e2e][ws]") {
    temp_dir dir;
    ws_server s(dir);
    child_process tcp(bin_dir + "/arena-bots",
                      {"--host", "127.0.0.1", "--port", std::to_string(s.tcp_port), "--bots", "2", "--duration", "3",
                       "--quiet", "--name-prefix", "tcp"},
                      dir.file("tcp.log"));
    const json j = run_bots(dir, "ws", s.http_port, {"--transport", "ws", "--bots", "8", "--duration", "3"});
    CHECK(j.at("joined") == 8);
    CHECK(j.at("failed") == 0);
    CHECK(j.at("ended_early") == 0);
    CHECK(j.at("disconnects").empty());
    CHECK(figure(j, "snapshots_per_s_per_bot", "min") >= 18.0);
    CHECK(figure(j, "snapshots_per_s_per_bot", "p50") == Approx(20.0).margin(0.5));
    CHECK(figure(j, "input_lag_ticks", "count") > 100);
    CHECK(figure(j, "input_lag_ticks", "p99") <= 3);
    CHECK(figure(j, "prediction_error_m", "count") > 100);
    const auto tcp_code = tcp.wait_for(30s);
    REQUIRE(tcp_code.has_value());
    CHECK(*tcp_code == 0);
    const std::string log = s.process.output();
    CHECK(log.find("name=ws-0") != std::string::npos);
    CHECK(log.find("name=tcp-0") != std::string::npos);
}

TEST_CASE("a WebSocket bot sending garbage is rejected alone, and the others play on", "[e2e][ws]") {
    temp_dir dir;
    ws_server s(dir);
    const json j = run_bots(
        dir, "mixed", s.http_port,
        {"--transport", "ws", "--bots", "4", "--duration", "3", "--misbehave", "garbage", "--misbehave-share", "0.25"});
    CHECK(j.at("joined") == 4);
    CHECK(j.at("misbehaving_dropped") == 1);
    CHECK(figure(j, "snapshots_per_s_per_bot", "p50") == Approx(20.0).margin(1.0));
    CHECK(s.process.output().find("code=bad_request") != std::string::npos);
}

TEST_CASE("arena-bots over WebSocket to a port without /ws fails with the upgrade's error", "[e2e][ws]") {
    temp_dir dir;
    ws_server s(dir);
    // The TCP game port speaks no HTTP: the upgrade cannot succeed.
    child_process p(bin_dir + "/arena-bots",
                    {"--transport", "ws", "--host", "127.0.0.1", "--port", std::to_string(s.tcp_port), "--bots", "1",
                     "--duration", "1", "--join-timeout", "2"},
                    dir.file("bots.log"));
    const auto code = p.wait_for(15s);
    REQUIRE(code.has_value());
    CHECK(*code == 1);
    CHECK(p.output().find("WebSocket upgrade of /ws") != std::string::npos);
}
