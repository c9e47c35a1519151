// The Agones SDK client against a fake sidecar on loopback: the order of the calls, the
// health ping period, pings pausing while the tick loop is stuck, retries while the sidecar
// is not up, and a bounded shutdown. Intervals are 100 ms instead of 2 s so that it runs fast.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <future>
#include <mutex>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include "server/ops/agones.hpp"
#include "server/ops/http_client.hpp"
#include "server/ops/ops_flags.hpp"
#include "tests/ops/loopback.hpp"

using namespace arena::ops;
using arena::test::fake_sidecar;
using arena::test::io_thread;
using arena::test::silent_listener;
using namespace std::chrono_literals;
using clock_type = std::chrono::steady_clock;

namespace {

agones_options fast_options(uint16_t port) {
    agones_options o;
    o.port = port;
    o.health_interval_ns = 100'000'000;
    o.request_timeout_ns = 300'000'000;
    o.retry_initial_ns = 50'000'000;
    o.retry_max_ns = 400'000'000;
    o.shutdown_timeout_ns = 1'000'000'000;
    return o;
}

// The client on its own io thread, with a healthy flag and a log the test can read.
struct client_fixture {
    std::atomic<bool> healthy{true};
    std::mutex log_mutex;
    std::vector<std::pair<clock_type::time_point, std::string>> log;
    boost::asio::io_context io;
    agones_client client;
    io_thread runner;

    explicit client_fixture(const agones_options& options)
        : client(
              io, options, [this] { return healthy.load(); },
              [this](const std::string& line) {
                  std::lock_guard lock(log_mutex);
                  log.emplace_back(clock_type::now(), line);
              }),
          runner(io) {}

    void start() {
        runner.run_on_io([this] { client.start(); });
    }
    // Calls shutdown on the io thread; the future is ready when `done` ran.
    std::future<clock_type::time_point> shutdown() {
        auto done = std::make_shared<std::promise<clock_type::time_point>>();
        auto result = done->get_future();
        runner.run_on_io([this, done] { client.shutdown([done] { done->set_value(clock_type::now()); }); });
        return result;
    }
    std::vector<clock_type::time_point> failures(const std::string& what) {
        std::lock_guard lock(log_mutex);
        std::vector<clock_type::time_point> at;
        for (const auto& [t, line] : log)
            if (line.find(what) != std::string::npos && line.find("failed") != std::string::npos) at.push_back(t);
        return at;
    }
};

auto count_of(const std::string& path, size_t n) {
    return [path, n](const std::vector<fake_sidecar::call>& calls) {
        return static_cast<size_t>(
                   std::count_if(calls.begin(), calls.end(), [&](auto& c) { return c.path == path; })) >= n;
    };
}

double ms_between(clock_type::time_point a, clock_type::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

}  // namespace

TEST_CASE("ops Agones: ready, then health pings at the interval, then shutdown, in that order", "[ops][agones]") {
    fake_sidecar sidecar;
    client_fixture f(fast_options(sidecar.port()));
    f.start();
    REQUIRE(sidecar.wait_until(count_of("/health", 6), 3s));
    auto done = f.shutdown();
    REQUIRE(done.wait_for(2s) == std::future_status::ready);

    const auto calls = sidecar.calls();
    REQUIRE(calls.size() >= 8);
    CHECK(calls.front().path == "/ready");
    CHECK(calls.back().path == "/shutdown");
    for (size_t i = 1; i + 1 < calls.size(); ++i) CHECK(calls[i].path == "/health");
    for (const auto& c : calls) {
        CHECK(c.method == "POST");
        CHECK(c.body == "{}");
    }
    // Pings every 100 ms: the median gap is about that, none is much shorter. (Loose upper
    // bound: ctest runs this beside every other test.)
    std::vector<double> gaps;
    for (size_t i = 2; i + 1 < calls.size(); ++i) gaps.push_back(ms_between(calls[i - 1].at, calls[i].at));
    std::sort(gaps.begin(), gaps.end());
    CHECK(gaps.front() > 50);
    CHECK(gaps[gaps.size() / 2] > 85);
    CHECK(gaps[gaps.size() / 2] < 250);
    // done comes after the sidecar saw /shutdown.
    CHECK(done.get() >= calls.back().at);
}

TEST_CASE("ops Agones: health pings stop while the tick loop is stuck and resume after", "[ops][agones]") {
    fake_sidecar sidecar;
    client_fixture f(fast_options(sidecar.port()));
    f.start();
    REQUIRE(sidecar.wait_until(count_of("/health", 3), 2s));
    f.healthy = false;
    std::this_thread::sleep_for(350ms);  // a ping already in flight may still land (timeout 300 ms)
    const size_t stuck = sidecar.count("/health");
    std::this_thread::sleep_for(600ms);  // six intervals without a ping
    CHECK(sidecar.count("/health") == stuck);
    f.healthy = true;
    CHECK(sidecar.wait_until(count_of("/health", stuck + 2), 1s));
    auto done = f.shutdown();
    CHECK(done.wait_for(2s) == std::future_status::ready);
}

TEST_CASE("ops Agones: /ready is retried with growing waits until a late sidecar answers", "[ops][agones]") {
    const uint16_t port = arena::test::free_port();
    fake_sidecar sidecar(port, 900ms);
    client_fixture f(fast_options(port));
    const auto started = clock_type::now();
    f.start();
    REQUIRE(sidecar.wait_until(count_of("/ready", 1), 3s));
    const auto calls = sidecar.calls();
    CHECK(calls.front().path == "/ready");
    // Answered soon after the sidecar came up: within one capped wait (400 ms) and some slack.
    CHECK(ms_between(sidecar.listening_since(), calls.front().at) < 1000);
    CHECK(ms_between(started, calls.front().at) >= 850);
    // Attempts at about 0, 50, 150, 350, 750 ms, not every 50 ms: the waits grow.
    const auto failed = f.failures("/ready");
    REQUIRE(failed.size() >= 4);
    CHECK(failed.size() <= 7);
    CHECK(ms_between(failed[failed.size() - 2], failed.back()) > 2.5 * ms_between(failed[0], failed[1]));
    CHECK(sidecar.wait_until(count_of("/health", 1), 1s));
    auto done = f.shutdown();
    CHECK(done.wait_for(2s) == std::future_status::ready);
}

TEST_CASE("ops Agones: /shutdown is retried while the sidecar errs, and done comes after it accepts", "[ops][agones]") {
    fake_sidecar sidecar;
    client_fixture f(fast_options(sidecar.port()));
    f.start();
    REQUIRE(sidecar.wait_until(count_of("/health", 1), 2s));
    sidecar.set_status(500);
    auto done = f.shutdown();
    REQUIRE(sidecar.wait_until(count_of("/shutdown", 2), 1s));
    CHECK(done.wait_for(0ms) == std::future_status::timeout);
    sidecar.set_status(200);
    REQUIRE(done.wait_for(2s) == std::future_status::ready);
    CHECK(sidecar.calls().back().path == "/shutdown");
}

TEST_CASE("ops Agones: without a sidecar, shutdown still ends within its timeout", "[ops][agones]") {
    agones_options options = fast_options(arena::test::free_port());
    options.shutdown_timeout_ns = 500'000'000;
    client_fixture f(options);
    f.start();
    std::this_thread::sleep_for(200ms);
    const auto asked = clock_type::now();
    auto done = f.shutdown();
    REQUIRE(done.wait_for(2s) == std::future_status::ready);
    const double waited = ms_between(asked, done.get());
    CHECK(waited > 450);
    CHECK(waited < 1200);
}

TEST_CASE("ops Agones flags: AGONES_SDK_HTTP_PORT turns it on unless --agones-port says otherwise", "[ops][agones]") {
    auto parse = [](std::vector<std::string> args, const char* env, ops_options& o) {
        CLI::App app;
        add_ops_flags(app, o);
        std::vector<const char*> argv{"arena-server"};
        for (auto& a : args) argv.push_back(a.c_str());
        app.parse(static_cast<int>(argv.size()), const_cast<char**>(argv.data()));
        return apply_agones_environment(o, env);
    };
    ops_options plain;
    CHECK(parse({}, nullptr, plain).empty());
    CHECK_FALSE(plain.agones);
    CHECK_FALSE(plain.metrics_port.has_value());

    ops_options from_env;
    CHECK(parse({"--metrics-port", "0"}, "9400", from_env).empty());
    CHECK(from_env.agones);
    CHECK(from_env.agones_sdk.port == 9400);
    CHECK(from_env.metrics_port == uint16_t{0});

    ops_options explicit_port;
    CHECK(parse({"--agones-port", "9500"}, "9400", explicit_port).empty());
    CHECK(explicit_port.agones_sdk.port == 9500);

    ops_options flag_only;
    CHECK(parse({"--agones"}, nullptr, flag_only).empty());
    CHECK(flag_only.agones);
    CHECK(flag_only.agones_sdk.port == 9358);

    ops_options bad;
    CHECK_FALSE(parse({}, "nine", bad).empty());
}

TEST_CASE("ops http client: a sidecar that takes the connection and never answers times out", "[ops][agones]") {
    silent_listener silent;

    boost::asio::io_context io;
    http_result result;
    const auto asked = clock_type::now();
    boost::asio::co_spawn(io, http_post(io.get_executor(), "127.0.0.1", silent.port(), "/ready", "{}", 300'000'000),
                          [&](std::exception_ptr, http_result r) { result = r; });
    io.run();
    const double waited = ms_between(asked, clock_type::now());
    CHECK(result.status == 0);
    CHECK(result.error == "timed out");
    CHECK(waited > 250);
    CHECK(waited < 1500);
}

TEST_CASE("ops http client: the status of a response is read, a malformed one is no status", "[ops][agones]") {
    fake_sidecar sidecar;
    sidecar.set_status(503);
    // The fake listens from its own thread: one request, no retries, so wait for it.
    const auto deadline = clock_type::now() + 2s;
    while (sidecar.listening_since() == clock_type::time_point{} && clock_type::now() < deadline)
        std::this_thread::sleep_for(5ms);
    // A server that answers with something other than HTTP.
    silent_listener not_http_server;  // accepted from below, by hand
    std::thread not_http([fd = not_http_server.fd()] {
        const int peer = accept(fd, nullptr, nullptr);
        const std::string banner = "SSH-2.0-OpenSSH_9.2\r\n\r\n";
        send(peer, banner.data(), banner.size(), MSG_NOSIGNAL);
        close(peer);
    });

    boost::asio::io_context io;
    http_result post, get, bad_address;
    auto keep = [](http_result& out) {
        return [&out](std::exception_ptr, http_result r) {
            out = r;
        };
    };
    boost::asio::co_spawn(io, http_post(io.get_executor(), "127.0.0.1", sidecar.port(), "/health", "{}", 1'000'000'000),
                          keep(post));
    boost::asio::co_spawn(
        io, http_get(io.get_executor(), "127.0.0.1", not_http_server.port(), "/healthz", 1'000'000'000), keep(get));
    boost::asio::co_spawn(io, http_get(io.get_executor(), "not-an-ip", sidecar.port(), "/", 1'000'000'000),
                          keep(bad_address));
    io.run();
    not_http.join();
    CHECK(post.status == 503);
    CHECK_FALSE(post.ok());
    CHECK(get.status == 0);
    CHECK_FALSE(get.error.empty());
    CHECK(bad_address.status == 0);
    CHECK(bad_address.error == "bad address not-an-ip");
    REQUIRE(sidecar.wait_until(count_of("/health", 1), 1s));
    CHECK(sidecar.calls().front().method == "POST");
    CHECK(sidecar.calls().front().body == "{}");
}
