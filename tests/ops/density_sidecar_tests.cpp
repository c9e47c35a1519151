// High density against a fake Agones sidecar on loopback (fake_sdk_server.hpp): the Counter
// `rooms` follows the matches, the List `players` follows the players, failures are retried,
// an undeclared key is left alone, the watch reconnects, and an allocation creates the match
// its annotations name without `rooms` counting it twice.
#include <catch2/catch.hpp>

#include <mutex>

#include "server/config/modes.hpp"
#include "server/host/match_registry.hpp"
#include "server/ops/agones.hpp"
#include "server/ops/density_sync.hpp"
#include "tests/ops/fake_sdk_server.hpp"
#include "tests/ops/loopback.hpp"

using namespace arena;
using namespace arena::ops;
using arena::test::fake_sdk_server;
using arena::test::io_thread;
using namespace std::chrono_literals;

namespace {

agones_options fast_options(uint16_t port) {
    agones_options o;
    o.port = port;
    o.health_interval_ns = 100'000'000;
    o.request_timeout_ns = 500'000'000;
    o.retry_initial_ns = 50'000'000;
    o.retry_max_ns = 200'000'000;
    o.shutdown_timeout_ns = 1'000'000'000;
    return o;
}

// The Agones client with high density on its own io thread; `on_allocation` runs there.
struct density_fixture {
    std::mutex log_mutex;
    std::vector<std::string> log;
    boost::asio::io_context io;
    agones_client client;
    io_thread runner;

    density_fixture(uint16_t port, std::function<void(const allocation_request&)> on_allocation = {})
        : client(
              io, fast_options(port), [] { return true; },
              [this](const std::string& line) {
                  std::lock_guard lock(log_mutex);
                  log.push_back(line);
              }),
          runner(io) {
        runner.run_on_io([this, on_allocation] {
            client.keep_density(on_allocation ? on_allocation : [](const allocation_request&) {});
        });
    }
    void start() {
        runner.run_on_io([this] { client.start(); });
    }
    void want(int64_t rooms, std::set<std::string> players = {}) {
        runner.run_on_io([&] { client.want_density(density_state{rooms, players}); });
    }
    size_t log_lines_with(const std::string& text) {
        std::lock_guard lock(log_mutex);
        return static_cast<size_t>(
            std::count_if(log.begin(), log.end(), [&](const std::string& l) { return l.find(text) != l.npos; }));
    }
};

std::vector<std::string> bodies_of(const fake_sdk_server& sidecar, const std::string& method, const std::string& path) {
    std::vector<std::string> out;
    for (const auto& c : sidecar.calls())
        if (c.method == method && c.path == path && c.status == 200) out.push_back(c.body);
    return out;
}

}  // namespace

TEST_CASE("density: rooms follows the matches as they are created and end", "[ops][agones][density]") {
    fake_sdk_server sidecar;
    density_fixture f(sidecar.port());
    f.want(1);
    f.start();
    REQUIRE(fake_sdk_server::wait_until([&] { return sidecar.rooms() == 1; }, 3s));
    f.want(4);
    REQUIRE(fake_sdk_server::wait_until([&] { return sidecar.rooms() == 4; }, 3s));
    f.want(2);
    REQUIRE(fake_sdk_server::wait_until([&] { return sidecar.rooms() == 2; }, 3s));
    // int64s as JSON strings, one PATCH per change.
    CHECK(bodies_of(sidecar, "PATCH", "/v1beta1/counters/rooms") ==
          std::vector<std::string>{R"({"countDiff":"1"})", R"({"countDiff":"3"})", R"({"countDiff":"-2"})"});
    CHECK(sidecar.count("GET", "/v1beta1/counters/rooms") >= 1);
    // The lifecycle goes on beside it.
    CHECK(sidecar.count("POST", "/ready") == 1);
}

TEST_CASE("density: the players List follows joins and leaves", "[ops][agones][density]") {
    fake_sdk_server sidecar;
    density_fixture f(sidecar.port());
    f.want(1, {"default/1", "default/2"});
    f.start();
    REQUIRE(fake_sdk_server::wait_until([&] { return sidecar.players().size() == 2; }, 3s));
    f.want(2, {"default/1", "m7/1"});
    REQUIRE(fake_sdk_server::wait_until(
        [&] {
            auto p = sidecar.players();
            std::sort(p.begin(), p.end());
            return p == std::vector<std::string>{"default/1", "m7/1"};
        },
        3s));
    CHECK(bodies_of(sidecar, "POST", "/v1beta1/lists/players:removeValue") ==
          std::vector<std::string>{R"({"value":"default/2"})"});
    CHECK(bodies_of(sidecar, "POST", "/v1beta1/lists/players:addValue").size() == 3);
    f.want(2, {});
    REQUIRE(fake_sdk_server::wait_until([&] { return sidecar.players().empty(); }, 3s));
    // Never a value twice: the fake refuses duplicates, and none was refused.
    for (const auto& c : sidecar.calls()) CHECK(c.status == 200);
}

TEST_CASE("density: a change the sidecar answers 500 is retried until it holds", "[ops][agones][density]") {
    fake_sdk_server sidecar;
    sidecar.fail_next("PATCH", "/v1beta1/counters/rooms", 500, 2);
    sidecar.fail_next("POST", "/v1beta1/lists/players:addValue", 503, 1);
    density_fixture f(sidecar.port());
    f.want(3, {"default/1"});
    f.start();
    REQUIRE(fake_sdk_server::wait_until([&] { return sidecar.rooms() == 3 && sidecar.players().size() == 1; }, 5s));
    std::vector<int> patches;
    for (const auto& c : sidecar.calls())
        if (c.method == "PATCH") patches.push_back(c.status);
    CHECK(patches == std::vector<int>{500, 500, 200});
    CHECK(sidecar.count("POST", "/v1beta1/lists/players:addValue") == 2);
    // Logged once, not once per retry.
    CHECK(f.log_lines_with("PATCH /v1beta1/counters/rooms failed: HTTP 500") == 1);
}

TEST_CASE("density: a GameServer that declares no Counter or List is not asked again", "[ops][agones][density]") {
    fake_sdk_server sidecar(fake_sdk_server::setup{std::nullopt, std::nullopt});
    density_fixture f(sidecar.port());
    f.want(2, {"default/1"});
    f.start();
    REQUIRE(fake_sdk_server::wait_until([&] { return f.log_lines_with("declares no List 'players'") >= 1; }, 3s));
    f.want(3, {"default/1", "default/2"});
    std::this_thread::sleep_for(300ms);
    CHECK(sidecar.count("PATCH", "/v1beta1/counters") == 0);
    CHECK(sidecar.count("POST", "/v1beta1/lists") == 0);
    CHECK(f.log_lines_with("declares no Counter 'rooms'") == 1);
    CHECK(f.log_lines_with("declares no List 'players'") == 1);
    const auto* sync = f.client.density();
    REQUIRE(sync);
    CHECK_FALSE(sync->reconciler().rooms_enabled());
}

TEST_CASE("density: the watch reconnects after the sidecar drops it", "[ops][agones][density]") {
    fake_sdk_server sidecar;
    density_fixture f(sidecar.port());
    f.want(1);
    f.start();
    REQUIRE(fake_sdk_server::wait_until([&] { return sidecar.watchers() == 1; }, 3s));
    sidecar.drop_watches();
    REQUIRE(fake_sdk_server::wait_until([&] { return sidecar.watchers() == 1; }, 3s));
    CHECK(sidecar.count("GET", "/watch/gameserver") == 2);
    // And the new stream is heard: an allocation through it is seen.
    REQUIRE(sidecar.allocate("sandbox", "after-drop"));
    CHECK(fake_sdk_server::wait_until([&] { return f.client.density()->allocations() == 1; }, 3s));
}

TEST_CASE("density: an allocation creates the match its annotations name, counted once", "[ops][agones][density]") {
    host::registry_options o;
    o.base.tick_rate = 60;
    o.base.snapshot_rate = 20;
    o.modes = config::builtin_modes();
    o.default_mode = "asteroids";
    o.max_matches = 8;
    host::match_registry registry(o);  // touched on the io thread only
    fake_sdk_server sidecar;

    agones_client* client = nullptr;
    auto want_now = [&] {
        client->want_density(density_state{static_cast<int64_t>(registry.size()), {}});
    };
    density_fixture f(sidecar.port(), [&](const allocation_request& a) {
        if (a.match.empty() || !registry.find(a.match))
            registry.create(a.mode.empty() ? "asteroids" : a.mode, true, "", a.match);
        want_now();
    });
    client = &f.client;
    f.want(1);
    f.start();
    REQUIRE(fake_sdk_server::wait_until([&] { return sidecar.rooms() == 1 && sidecar.watchers() == 1; }, 3s));

    REQUIRE(sidecar.allocate("sandbox", "finals"));  // rooms 2: the allocator counted it
    std::string mode;
    REQUIRE(fake_sdk_server::wait_until(
        [&] {
            f.runner.run_on_io([&] {
                const host::hosted_match* m = registry.find("finals");
                mode = m ? m->mode : "";
            });
            return !mode.empty();
        },
        3s));
    CHECK(mode == "sandbox");
    std::this_thread::sleep_for(300ms);  // time for a wrong +1 to land, if one were sent
    CHECK(sidecar.rooms() == 2);
    CHECK(bodies_of(sidecar, "PATCH", "/v1beta1/counters/rooms") == std::vector<std::string>{R"({"countDiff":"1"})"});

    // The same match allocated again: nothing created, and the allocator's +1 taken back.
    REQUIRE(sidecar.allocate("sandbox", "finals"));
    REQUIRE(fake_sdk_server::wait_until([&] { return f.client.density()->allocations() == 2; }, 3s));
    REQUIRE(fake_sdk_server::wait_until([&] { return sidecar.rooms() == 2; }, 3s));
    // No id: a new match with a random one.
    REQUIRE(sidecar.allocate("", ""));
    REQUIRE(fake_sdk_server::wait_until([&] { return f.client.density()->allocations() == 3; }, 3s));
    size_t matches = 0;
    f.runner.run_on_io([&] { matches = registry.size(); });
    CHECK(matches == 3);
    std::this_thread::sleep_for(300ms);
    CHECK(sidecar.rooms() == 3);
}
