#pragma once
// What the end-to-end tests of each transport share: arena-server with a second transport
// beside TCP, and the figures of an arena-bots --json report.
#include <catch2/catch.hpp>

#include <csignal>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "process.hpp"

namespace arena::test {

// arena-server on loopback (the asteroids preset, seed 1, at most 30 s) with a second transport
// on port 0 of `port_flag` ("--udp-port", "--http-port"), once it printed both its "listening
// on" line and the second transport's ("udp listening on", "http listening on"), with `more`
// flags after these. SIGTERM at the end.
struct server_beside_tcp {
    child_process process;
    unsigned tcp_port = 0;
    unsigned second_port = 0;

    server_beside_tcp(const std::string& bin_dir, const temp_dir& dir, const std::string& port_flag,
                      const std::string& port_line, std::vector<std::string> more = {})
        : process(
              bin_dir + "/arena-server",
              [&] {
                  // The sandbox's rules, which these tests of transports and prediction measure
                  // (the asteroids preset plays its own rules unless told).
                  std::vector<std::string> args = {"--bind", "127.0.0.1", "--port",     "0",       port_flag,
                                                   "0",      "--preset",  "asteroids",  "--rules", "sandbox",
                                                   "--seed", "1",         "--duration", "30"};
                  args.insert(args.end(), more.begin(), more.end());
                  return args;
              }(),
              dir.file("server.log")) {
        using namespace std::chrono_literals;
        const auto t = wait_for_listening(process, 5s);
        const auto s = wait_for_port_line(process, port_line, 5s);
        if (!t || !s) FAIL("arena-server did not print both listening lines: " << process.output());
        tcp_port = *t;
        second_port = *s;
    }
    ~server_beside_tcp() {
        using namespace std::chrono_literals;
        process.signal(SIGTERM);
        process.wait_for(3s);
    }
    server_beside_tcp(const server_beside_tcp&) = delete;
    server_beside_tcp& operator=(const server_beside_tcp&) = delete;
};

// One statistic ("p99", "min", "count", ...) of one figure of an arena-bots --json report.
inline double figure(const nlohmann::json& report, const std::string& name, const std::string& stat) {
    return report.at("figures").at(name).at(stat).get<double>();
}

}  // namespace arena::test
