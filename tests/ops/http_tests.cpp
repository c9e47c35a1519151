// The ops HTTP endpoint: routing as a pure function, then the real server over loopback.
#include <catch2/catch.hpp>

#include <atomic>
#include <cstdlib>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include "common/run_command.hpp"
#include "server/ops/http_routes.hpp"
#include "server/ops/http_server.hpp"
#include "server/ops/metrics.hpp"
#include "server/ops/ops_flags.hpp"
#include "server/ops/ops_service.hpp"
#include "tests/ops/loopback.hpp"

using namespace arena::ops;
using arena::test::http_exchange;
using arena::test::http_get;
using arena::test::io_thread;
using arena::test::silent_listener;
using arena::test::status_of;

namespace {

// A server on a free loopback port with a healthy flag the test flips.
struct endpoint_fixture {
    std::atomic<bool> healthy{true};
    std::atomic<int> scrapes{0};
    boost::asio::io_context io;
    http_server server;
    io_thread runner;

    explicit endpoint_fixture(http_server_options options = {})
        : server(io, options,
                 http_handlers{[this] {
                                   ++scrapes;
                                   return std::string("arena_ticks_total 7\n");
                               },
                               [this] {
                                   return healthy.load();
                               }}),
          runner(io) {
        runner.run_on_io([this] { server.start(); });
    }
};

std::string body_of(const std::string& response) {
    const size_t at = response.find("\r\n\r\n");
    return at == std::string::npos ? "" : response.substr(at + 4);
}

}  // namespace

TEST_CASE("ops http: routing: /metrics, /healthz by the health function, 404 and 405", "[ops][http]") {
    bool healthy = true;
    const http_handlers h{[] { return std::string("m 1\n"); },
                          [&] {
                              return healthy;
                          }};
    CHECK(route({"GET", "/metrics"}, h).status == 200);
    CHECK(route({"GET", "/metrics"}, h).content_type == metrics_content_type);
    CHECK(route({"GET", "/healthz"}, h).status == 200);
    healthy = false;
    CHECK(route({"GET", "/healthz"}, h).status == 503);
    CHECK(route({"GET", "/"}, h).status == 404);
    CHECK(route({"POST", "/metrics"}, h).status == 405);
    CHECK(route({"GET", "/healthz"}, http_handlers{}).status == 503);
}

TEST_CASE("ops http: GET /metrics over HTTP returns the text format", "[ops][http]") {
    endpoint_fixture f;
    const std::string response = http_get(f.server.port(), "/metrics");
    CHECK(status_of(response) == 200);
    CHECK(response.find("Content-Type: text/plain; version=0.0.4") != std::string::npos);
    CHECK(response.find("Connection: close") != std::string::npos);
    CHECK(body_of(response) == "arena_ticks_total 7\n");
    CHECK(f.scrapes == 1);
}

TEST_CASE("ops http: GET /healthz is 200 while healthy and 503 while the tick loop is stuck", "[ops][http]") {
    endpoint_fixture f;
    CHECK(status_of(http_get(f.server.port(), "/healthz")) == 200);
    CHECK(body_of(http_get(f.server.port(), "/healthz")) == "ok\n");
    f.healthy = false;
    CHECK(status_of(http_get(f.server.port(), "/healthz")) == 503);
    f.healthy = true;
    CHECK(status_of(http_get(f.server.port(), "/healthz")) == 200);
}

TEST_CASE("ops http: malformed request heads get 400 or 505 over the wire, the query string is ignored",
          "[ops][http]") {
    endpoint_fixture f;
    auto status = [&](const std::string& head) {
        return status_of(http_exchange(f.server.port(), head));
    };
    CHECK(status("GET /metrics?x=1 HTTP/1.1\r\nHost: a\r\n\r\n") == 200);
    CHECK(status("GET /healthz HTTP/1.0\r\n\r\n") == 200);
    CHECK(status("GET /metrics\r\n\r\n") == 400);
    CHECK(status("GET  /metrics HTTP/1.1\r\n\r\n") == 400);
    CHECK(status("get /metrics HTTP/1.1\r\n\r\n") == 400);
    CHECK(status("GET metrics HTTP/1.1\r\n\r\n") == 400);
    CHECK(status("GET /metrics HTTP/2.0\r\n\r\n") == 505);
    CHECK(status(std::string("GET /a\x01 HTTP/1.1\r\n\r\n")) == 400);
    CHECK(status("GET /metrics HTTP/1.1\r\nBad Header\r\n\r\n") == 400);
    CHECK(f.scrapes == 1);
}

TEST_CASE("ops http: a request with bare LF line endings gets 400 at once, not silence until the deadline",
          "[ops][http]") {
    endpoint_fixture f;  // 5 s to send a head, as in production
    for (const std::string head : {"GET /healthz HTTP/1.1\n\n", "GET /healthz HTTP/1.1\nHost: a\n\n",
                                   "GET /healthz HTTP/1.1\r\nHost: a\n\r\n", "GET /healthz HTTP/1.0\n"}) {
        const auto start = std::chrono::steady_clock::now();
        const std::string response = http_exchange(f.server.port(), head);
        const auto waited = std::chrono::steady_clock::now() - start;
        CHECK(status_of(response) == 400);
        CHECK(body_of(response) == "bare LF line ending: HTTP lines end in CRLF\n");
        CHECK(waited < std::chrono::milliseconds(1000));
    }
    // A head still arriving is not refused for a CR that is waiting for its LF.
    CHECK(http_exchange(f.server.port(), "GET /healthz HTTP/1.1\r", std::chrono::milliseconds(300)).empty());
    CHECK(f.scrapes == 0);
}

TEST_CASE("ops http: HEAD /healthz is answered like GET, without the body (load balancers' probes)", "[ops][http]") {
    endpoint_fixture f;
    const std::string head = http_exchange(f.server.port(), "HEAD /healthz HTTP/1.1\r\nHost: x\r\n\r\n");
    CHECK(status_of(head) == 200);
    CHECK(head.find("Content-Length: 3") != std::string::npos);
    CHECK(body_of(head).empty());
}

TEST_CASE("ops http: unknown paths are 404, other methods 405, garbage 400", "[ops][http]") {
    endpoint_fixture f;
    CHECK(status_of(http_get(f.server.port(), "/")) == 404);
    CHECK(status_of(http_get(f.server.port(), "/metrics/../etc/passwd")) == 404);
    CHECK(status_of(http_exchange(f.server.port(), "POST /metrics HTTP/1.1\r\nContent-Length: 0\r\n\r\n")) == 405);
    CHECK(status_of(http_exchange(f.server.port(), "hello\r\n\r\n")) == 400);
    CHECK(f.scrapes == 0);
}

TEST_CASE("ops http: a request head over the limit gets 431 and the connection closes", "[ops][http]") {
    http_server_options options;
    options.max_request_bytes = 1024;
    endpoint_fixture f(options);
    const std::string big = "GET /metrics HTTP/1.1\r\nX-Filler: " + std::string(4000, 'a') + "\r\n\r\n";
    CHECK(status_of(http_exchange(f.server.port(), big)) == 431);
    // A head just under the limit is still served.
    const std::string fits = "GET /metrics HTTP/1.1\r\nX-Filler: " + std::string(900, 'a') + "\r\n\r\n";
    CHECK(status_of(http_exchange(f.server.port(), fits)) == 200);
}

TEST_CASE("ops http: a client that never finishes its request is cut off after the read timeout", "[ops][http]") {
    http_server_options options;
    options.read_timeout_ns = 200'000'000;
    endpoint_fixture f(options);
    const auto start = std::chrono::steady_clock::now();
    const std::string response =
        http_exchange(f.server.port(), "GET /metrics HTTP/1.1\r\n", std::chrono::milliseconds(3000));
    const auto waited = std::chrono::steady_clock::now() - start;
    CHECK(response.empty());
    CHECK(waited < std::chrono::milliseconds(1500));
    // The server is still there for the next client.
    CHECK(status_of(http_get(f.server.port(), "/healthz")) == 200);
}

TEST_CASE("ops http: 40 idle connections do not lock /healthz out: the oldest idle one makes room", "[ops][http]") {
    http_server_options options;
    options.first_byte_timeout_ns = 10'000'000'000;  // only eviction can make room here
    endpoint_fixture f(options);
    std::vector<int> idle;
    for (int i = 0; i < 40; ++i) idle.push_back(arena::test::open_idle_connection(f.server.port()));
    // Each of the last 8 took the slot of one of the first 8.
    CHECK(arena::test::closed_by_peer(idle[0], std::chrono::milliseconds(3000)));
    CHECK(arena::test::closed_by_peer(idle[7], std::chrono::milliseconds(3000)));
    for (int round = 0; round < 3; ++round) {
        const auto start = std::chrono::steady_clock::now();
        CHECK(status_of(http_get(f.server.port(), "/healthz")) == 200);
        // Far below the 10 s any deadline here would take: eviction made the room.
        CHECK(std::chrono::steady_clock::now() - start < std::chrono::milliseconds(3000));
    }
    // The first probe took the oldest idle slot and gave it back when answered, so the next
    // ones found it free; the newest idle connections are still open.
    CHECK(arena::test::closed_by_peer(idle[8], std::chrono::milliseconds(200)));
    CHECK_FALSE(arena::test::closed_by_peer(idle[39], std::chrono::milliseconds(50)));
    std::uint32_t open = 0;
    uint64_t evicted = 0;
    f.runner.run_on_io([&] {
        open = f.server.open_connections();
        evicted = f.server.evicted_connections();
    });
    CHECK(open <= options.max_connections);
    CHECK(evicted == 8 + 1);
    for (int fd : idle) close(fd);
}

TEST_CASE("ops http: a connection that sends nothing is closed after the first-byte timeout", "[ops][http]") {
    http_server_options options;
    options.first_byte_timeout_ns = 200'000'000;
    endpoint_fixture f(options);
    const int idle = arena::test::open_idle_connection(f.server.port());
    const int slow = arena::test::open_idle_connection(f.server.port());
    REQUIRE(send(slow, "GET /healthz HTTP/1.1\r\n", 23, MSG_NOSIGNAL) == 23);
    const auto start = std::chrono::steady_clock::now();
    CHECK(arena::test::closed_by_peer(idle, std::chrono::milliseconds(2000)));
    const auto waited = std::chrono::steady_clock::now() - start;
    CHECK(waited < std::chrono::milliseconds(1000));
    // A client that has started its head gets the whole read timeout (5 s) to finish it.
    CHECK_FALSE(arena::test::closed_by_peer(slow, std::chrono::milliseconds(300)));
    REQUIRE(send(slow, "\r\n", 2, MSG_NOSIGNAL) == 2);
    const std::string response = arena::test::read_until_closed(slow, std::chrono::milliseconds(2000));
    CHECK(status_of(response) == 200);
    close(idle);
    close(slow);
}

TEST_CASE("ops http: arena-healthcheck exits 0 on 200 and 1 on 503 or no server", "[ops][http]") {
    endpoint_fixture f;
    const std::string probe = std::string(ARENA_BIN_DIR) +
                              "/arena-healthcheck http://127.0.0.1:" + std::to_string(f.server.port()) +
                              "/healthz --timeout 2 >/dev/null";
    CHECK(std::system(probe.c_str()) == 0);
    f.healthy = false;
    CHECK(WEXITSTATUS(std::system(probe.c_str())) == 1);
    const std::string nobody = std::string(ARENA_BIN_DIR) +
                               "/arena-healthcheck http://127.0.0.1:" + std::to_string(arena::test::free_port()) +
                               "/healthz --timeout 1 >/dev/null";
    CHECK(WEXITSTATUS(std::system(nobody.c_str())) == 1);
}

TEST_CASE("ops http: arena-healthcheck prints what it got, exits 2 on usage errors and 1 on a silent server",
          "[ops][http]") {
    using arena::test::program;
    using arena::test::run_command;
    endpoint_fixture f;
    const std::string url = "http://127.0.0.1:" + std::to_string(f.server.port()) + "/healthz";
    const auto ok = run_command(program("arena-healthcheck") + " " + url);
    CHECK(ok.exit_code == 0);
    CHECK(ok.output == "127.0.0.1:" + std::to_string(f.server.port()) + "/healthz -> 200\n");
    CHECK(run_command(program("arena-healthcheck") + " " + url + " --help").exit_code == 0);
    CHECK(run_command(program("arena-healthcheck") + " " + url + " --timeout 0 2>&1").exit_code == 2);
    CHECK(run_command(program("arena-healthcheck") + " " + url + " --timeout nan 2>&1").exit_code == 2);
    CHECK(run_command(program("arena-healthcheck") + " " + url + " --bogus 2>&1").exit_code == 2);
    CHECK(run_command(program("arena-healthcheck") + " ftp://127.0.0.1:1/ 2>&1").exit_code == 2);
    CHECK(run_command(program("arena-healthcheck") + " http://127.0.0.1:0/ 2>&1").exit_code == 2);
    CHECK(run_command(program("arena-healthcheck") + " http://localhost:80/ 2>&1").exit_code == 1);

    // Takes the connection and never answers: the probe gives up at its timeout.
    silent_listener endpoint_that_never_answers;
    const auto start = std::chrono::steady_clock::now();
    const auto silent = run_command(program("arena-healthcheck") + " http://127.0.0.1:" +
                                    std::to_string(endpoint_that_never_answers.port()) + "/healthz --timeout 0.3");
    const auto waited = std::chrono::steady_clock::now() - start;
    CHECK(silent.exit_code == 1);
    CHECK(silent.output.find("-> 0") != std::string::npos);
    CHECK(waited >= std::chrono::milliseconds(250));
    CHECK(waited < std::chrono::milliseconds(2000));
}

TEST_CASE("ops http: --metrics-bind puts the endpoints on their own address, apart from --bind", "[ops][http]") {
    ops_options options;
    options.bind = "127.0.0.1";
    options.metrics_bind = "127.0.0.2";  // a private address, while the game is on --bind
    options.metrics_port = 0;
    boost::asio::io_context io;
    std::vector<std::string> log;
    ops_service ops(
        io, options, [] { return server_metrics{}; }, [] { return true; },
        [&log](const std::string& line) { log.push_back(line); });
    io_thread runner(io);
    runner.run_on_io([&] { ops.start_after_listening(); });
    const uint16_t port = ops.metrics_port();
    REQUIRE(port != 0);
    CHECK(status_of(arena::test::http_get_at("127.0.0.2", port, "/healthz")) == 200);
    CHECK(arena::test::http_get_at("127.0.0.1", port, "/healthz").empty());  // nobody there
    REQUIRE_FALSE(log.empty());
    CHECK(log.front() == "metrics on http://127.0.0.2:" + std::to_string(port) + "/metrics");
}

TEST_CASE("ops flags: --metrics-bind takes an IP address and defaults to --bind", "[ops][http]") {
    auto parse = [](std::vector<std::string> args, ops_options& o) {
        CLI::App app;
        add_ops_flags(app, o);
        std::vector<const char*> argv{"arena-server"};
        for (auto& a : args) argv.push_back(a.c_str());
        app.parse(static_cast<int>(argv.size()), const_cast<char**>(argv.data()));
    };
    boost::asio::io_context io;
    ops_options plain;
    plain.bind = "0.0.0.0";
    parse({"--metrics-port", "9100"}, plain);
    CHECK(ops_service(io, plain, {}, {}).metrics_address() == "0.0.0.0");

    ops_options private_address;
    private_address.bind = "0.0.0.0";
    parse({"--metrics-port", "9100", "--metrics-bind", "10.0.0.5"}, private_address);
    CHECK(private_address.metrics_bind == "10.0.0.5");
    CHECK(ops_service(io, private_address, {}, {}).metrics_address() == "10.0.0.5");

    ops_options v6;
    parse({"--metrics-bind", "::1"}, v6);
    CHECK(v6.metrics_bind == "::1");

    ops_options bad;
    CHECK_THROWS_AS(parse({"--metrics-bind", "localhost"}, bad), CLI::ValidationError);
    CHECK_THROWS_AS(parse({"--metrics-bind", "10.0.0.300"}, bad), CLI::ValidationError);
}
