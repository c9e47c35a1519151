// arena-bots --transport udp against arena-server --udp-port, as real processes on loopback:
// UDP and TCP players in the same match, and the bots' simulated latency.
#include <signal.h>

#include <catch2/catch.hpp>
#include <fstream>
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

// arena-server with --udp-port beside TCP.
struct udp_server : arena::test::server_beside_tcp {
    explicit udp_server(const temp_dir& dir, std::vector<std::string> more = {})
        : server_beside_tcp(bin_dir, dir, "--udp-port", "udp listening on", std::move(more)), udp_port(second_port) {}
    const unsigned udp_port;
};

// Starts arena-bots; the report is read once it exited.
struct bots {
    std::string report_file;
    child_process process;
    bots(const temp_dir& dir, const std::string& name, unsigned port, std::vector<std::string> args)
        : report_file(dir.file(name + ".json")),
          process(
              bin_dir + "/arena-bots",
              [&] {
                  args.insert(args.end(), {"--host", "127.0.0.1", "--port", std::to_string(port), "--json", report_file,
                                           "--quiet", "--name-prefix", name});
                  return args;
              }(),
              dir.file(name + ".log")) {}
    json finish() {
        const auto code = process.wait_for(30s);
        INFO(process.output());
        REQUIRE(code.has_value());
        CHECK(*code == 0);
        const std::string text = arena::test::read_file(report_file);
        REQUIRE(!text.empty());
        return json::parse(text);
    }
};

void check_everyone_played(const json& j, int n) {
    CHECK(j.at("joined") == n);
    CHECK(j.at("failed") == 0);
    CHECK(j.at("ended_early") == 0);
    CHECK(j.at("disconnects").empty());
    CHECK(figure(j, "snapshots_per_s_per_bot", "min") >= 18.0);
    CHECK(figure(j, "snapshots_per_s_per_bot", "p50") == Approx(20.0).margin(0.5));
    // Inputs were consumed: every snapshot's ack names an input the world applied.
    CHECK(figure(j, "input_lag_ticks", "count") > 100);
}

}  // namespace

TEST_CASE("UDP bots and TCP bots play in the same match at the snapshot rate", "[e2e][udp]") {
    temp_dir dir;
    udp_server s(dir);
    bots udp(dir, "udp", s.udp_port, {"--transport", "udp", "--bots", "12", "--duration", "4", "--seed", "3"});
    bots tcp(dir, "tcp", s.tcp_port, {"--bots", "4", "--duration", "4", "--seed", "4"});
    const json u = udp.finish();
    const json t = tcp.finish();
    check_everyone_played(u, 12);
    check_everyone_played(t, 4);
    // Loopback without loss: an input is consumed at the next tick or the one after.
    CHECK(figure(u, "input_lag_ticks", "p99") <= 3);
    CHECK(figure(u, "rtt_ms", "p50") < 20.0);
    // Both kinds of players were in one world: the server logged joins from both prefixes.
    const std::string log = s.process.output();
    CHECK(log.find("name=udp-0") != std::string::npos);
    CHECK(log.find("name=tcp-0") != std::string::npos);
}

TEST_CASE("UDP bots' simulated latency shows in their round trip and input lag", "[e2e][udp]") {
    temp_dir dir;
    udp_server s(dir);
    bots udp(
        dir, "late", s.udp_port,
        {"--transport", "udp", "--bots", "4", "--duration", "3", "--simulate-latency", "40", "--simulate-jitter", "5"});
    const json j = udp.finish();
    check_everyone_played(j, 4);
    // 40 ms each way ± 5: a round trip of 75 to 85 ms, plus loopback and the server's turn.
    CHECK(figure(j, "rtt_ms", "p50") >= 75.0);
    CHECK(figure(j, "rtt_ms", "p50") < 130.0);
    // 40 ms is 2.4 ticks at 60 Hz before the input arrives.
    CHECK(figure(j, "input_lag_ticks", "p50") >= 2);
}

TEST_CASE("arena-bots refuses a simulated latency over TCP: it delays datagrams", "[e2e][udp]") {
    temp_dir dir;
    child_process p(bin_dir + "/arena-bots", {"--simulate-latency", "10", "--duration", "1"}, dir.file("bots.log"));
    const auto code = p.wait_for(10s);
    REQUIRE(code.has_value());
    CHECK(*code == 2);
    CHECK(p.output().find("need --transport udp") != std::string::npos);
}

TEST_CASE("with --token-secret UDP bots holding the secret join, and bots without the connect key get no peer",
          "[e2e][udp][auth]") {
    temp_dir dir;
    const std::string secret = dir.file("token-secret");
    std::ofstream(secret) << "0123456789abcdef0123456789abcdef-e2e-udp-key";
    udp_server s(dir, {"--token-secret", secret});
    // The bots mint their tokens and derive the connect key from the same secret file.
    bots honest(dir, "keyed", s.udp_port,
                {"--transport", "udp", "--bots", "4", "--duration", "3", "--token-secret", secret});
    check_everyone_played(honest.finish(), 4);

    // Without the secret a bot puts no key in ENet's connect: the gate refuses it before ENet
    // gives it a peer, so it never gets as far as its Hello.
    bots keyless(dir, "keyless", s.udp_port,
                 {"--transport", "udp", "--bots", "2", "--duration", "2", "--join-timeout", "2"});
    const auto code = keyless.process.wait_for(30s);
    REQUIRE(code.has_value());
    CHECK(*code == 1);
    const json k = json::parse(arena::test::read_file(keyless.report_file));
    CHECK(k.at("joined") == 0);
    CHECK(k.at("failed") == 2);
    CHECK(s.process.output().find("a connect without this server's connect key") != std::string::npos);
}
