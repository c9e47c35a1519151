// arena-server end to end over loopback, at its limits: refusals by code, garbage, a client that
// never reads, a thousand connections at once, no file descriptors left.
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <thread>

#include "common/run_command.hpp"
#include "protocol/decode.hpp"
#include "protocol/version.hpp"
#include "server_process.hpp"
#include "tcp_test_client.hpp"

using namespace arena;
using namespace arena::test;
using namespace std::chrono_literals;
using protocol::Payload;

TEST_CASE("version mismatch, a full server and a missing hello are rejected with their codes", "[net][e2e]") {
    server_process server({"--max-players", "1", "--handshake-timeout", "0.3"});
    {
        test_client c(server.port());
        c.send_frame(protocol::encode_hello(protocol::protocol_version + 1, "future", ""));
        CHECK(expect_reject(c).code == protocol::RejectCode::version_mismatch);
    }
    joined_client first(server.port());
    {
        test_client c(server.port());
        c.send_frame(protocol::encode_hello(protocol::protocol_version, "second", ""));
        CHECK(expect_reject(c).code == protocol::RejectCode::server_full);
    }
    {
        test_client c(server.port());
        CHECK(expect_reject(c).code == protocol::RejectCode::timeout);
    }
}

TEST_CASE("garbage, an oversize length and a NaN input close only that client", "[net][e2e]") {
    server_process server({});
    joined_client good(server.port(), "good");
    struct bad_case {
        const char* name;
        std::function<void(test_client&)> misbehave;
        protocol::RejectCode expected;
    };
    const std::vector<bad_case> cases = {
        {"garbage",
         [](test_client& c) { c.send_bytes({16, 0, 0, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16}); },
         protocol::RejectCode::bad_request},
        {"oversize",
         [](test_client& c) {
             c.send_bytes({0x01, 0x00, 0x01, 0x00});
         },
         protocol::RejectCode::too_large},
        {"nan",
         [](test_client& c) {
             c.send_frame(protocol::encode_input({1, std::numeric_limits<float>::quiet_NaN(), 0, 0}));
         },
         protocol::RejectCode::bad_input},
    };
    for (const auto& bad : cases) {
        INFO(bad.name);
        joined_client offender(server.port(), bad.name);
        bad.misbehave(offender.client);
        CHECK(expect_reject(offender.client).code == bad.expected);
    }
    // The good client kept its full snapshot rate throughout, and still does.
    CHECK(count_snapshots(good.client, 1000ms) >= 18);
    const std::string log = server.log();
    CHECK(log.find("code=too_large") != std::string::npos);
    CHECK(log.find("code=bad_input") != std::string::npos);
}

TEST_CASE("a client that never reads keeps the server's memory bounded and is dropped", "[net][e2e]") {
    // 1000 rocks: each snapshot of the whole world (--view-radius 0) is about 32 KB; with a
    // 4 KiB receive buffer on the sleeper and a 64 KiB send buffer on the server, an unread
    // socket fills within a second.
    const std::string config = temp_path("big.json");
    std::ofstream(config) << R"({"preset": "asteroids", "size": [2000, 2000], "rocks": {"count": 1000}})";
    server_process server(
        {"--config", config, "--stall-timeout", "1", "--socket-send-buffer", "65536", "--view-radius", "0"});
    joined_client good(server.port(), "good");
    joined_client sleeper(server.port(), "sleeper", 4096);  // never reads again
    count_snapshots(good.client, 500ms);
    const long rss_before = server.rss_kib();
    CHECK(count_snapshots(good.client, 3000ms) >= 50);
    const long rss_after = server.rss_kib();
    INFO("rss before " << rss_before << " KiB, after " << rss_after << " KiB");
    CHECK(rss_after - rss_before < 4096);  // at most one pending snapshot per client
    CHECK(server.log_shows("code=slow_consumer"));
    CHECK(count_snapshots(good.client, 1000ms) >= 18);
    std::remove(config.c_str());
}
TEST_CASE("a thousand connections opened at once are refused beyond the limits while players play on",
          "[net][e2e][limits]") {
    const std::string stats = temp_path("flood-stats.json");
    server_process server({"--max-pending-handshakes", "32", "--handshake-timeout", "1", "--stats-json", stats});
    joined_client good(server.port(), "good");
    const long rss_before = server.rss_kib();
    std::vector<std::unique_ptr<test_client>> crowd;
    for (int i = 0; i < 1000; ++i) crowd.push_back(std::make_unique<test_client>(server.port()));
    const auto crowd_in = std::chrono::steady_clock::now();
    CHECK(count_snapshots(good.client, 2000ms) >= 36);
    // Every silent connection is gone: refused at once or timed out without a Hello. The last
    // to be accepted times out a second after its accept, which a loaded machine may delay.
    const auto deadline = crowd_in + 4s;
    int closed = 0;
    for (auto& c : crowd) {
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
        closed += c->closed_by_peer(std::max(left, 10ms)) ? 1 : 0;
    }
    CHECK(closed == 1000);
    CHECK(server.rss_kib() - rss_before < 16384);
    CHECK(count_snapshots(good.client, 1000ms) >= 18);
    crowd.clear();
    REQUIRE(server.stop(SIGTERM) == 0);
    const std::string text = read_file(stats);
    CHECK(text.find("\"max_pending_handshakes\": 32") != std::string::npos);
    // Not server_full: the server was never full. The oldest waiting connections gave their
    // slots to newer ones.
    CHECK(text.find("\"server_full\"") == std::string::npos);
    CHECK(text.find("\"too_many_waiting\"") != std::string::npos);
    CHECK(text.find("\"timeout\"") != std::string::npos);
    std::remove(stats.c_str());
}

namespace {

// CPU seconds (user + system) a process has used, from /proc.
double cpu_seconds(pid_t pid) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::istringstream fields(text.substr(text.rfind(')') + 2));  // after the command's name
    std::string field;
    unsigned long long utime = 0, stime = 0;
    for (int k = 3; k <= 15 && fields >> field; ++k) {
        if (k == 14) utime = std::stoull(field);
        if (k == 15) stime = std::stoull(field);
    }
    return static_cast<double>(utime + stime) / static_cast<double>(::sysconf(_SC_CLK_TCK));
}

}  // namespace

TEST_CASE("out of descriptors the accept loop pauses and logs at a bounded rate", "[net][e2e][limits]") {
    // The server inherits a limit of 40 descriptors; 60 clients connect. Accept failed with
    // EMFILE and was retried at once: a core at 100 % and millions of log lines in seconds.
    rlimit old{};
    REQUIRE(::getrlimit(RLIMIT_NOFILE, &old) == 0);
    rlimit low = old;
    low.rlim_cur = 40;
    REQUIRE(::setrlimit(RLIMIT_NOFILE, &low) == 0);
    std::unique_ptr<server_process> server;
    try {
        server = std::make_unique<server_process>(std::vector<std::string>{"--max-connections", "100"});
    } catch (...) {
        ::setrlimit(RLIMIT_NOFILE, &old);
        throw;
    }
    ::setrlimit(RLIMIT_NOFILE, &old);
    CHECK(server->log_shows("exceeds the descriptor limit 40"));
    std::vector<std::unique_ptr<test_client>> crowd;
    for (int i = 0; i < 60; ++i) crowd.push_back(std::make_unique<test_client>(server->port()));
    CHECK(server->log_shows("game: accept failed: Too many open files"));
    const double cpu_before = cpu_seconds(server->pid());
    std::this_thread::sleep_for(2s);
    const double cpu = cpu_seconds(server->pid()) - cpu_before;
    INFO("server CPU in 2 s: " << cpu << " s");
    CHECK(cpu < 0.5);
    const std::string log = server->log();
    size_t lines = 0;
    for (size_t at = log.find("accept failed"); at != std::string::npos; at = log.find("accept failed", at + 1))
        ++lines;
    CHECK(lines <= 2);  // one line per 10 s at most
    // Once descriptors are free again (the idle crowd times out), a player joins.
    crowd.clear();
    std::this_thread::sleep_for(1500ms);
    joined_client late(server->port(), "late");
    CHECK(count_snapshots(late.client, 1000ms) >= 10);
}
