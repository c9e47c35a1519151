// arena-server as a process against a fake Agones sidecar (tests/ops/fake_sdk_server.hpp):
// an allocation through the sidecar creates the match its annotations name, a client joins it
// by Hello.match, and the sidecar's Counter `rooms` and List `players` follow.
#include <catch2/catch.hpp>

#include <csignal>

#include "protocol/decode.hpp"
#include "protocol/messages.hpp"
#include "protocol/version.hpp"
#include "tests/net/server_process.hpp"
#include "tests/ops/fake_sdk_server.hpp"

using namespace arena;
using arena::test::fake_sdk_server;
using arena::test::server_process;
using arena::test::test_client;
using namespace std::chrono_literals;

TEST_CASE("agones e2e: an allocated match appears, takes a player, and rooms counts it once",
          "[e2e][agones][density]") {
    fake_sdk_server sidecar(fake_sdk_server::setup{8, 64});
    server_process server(
        {"--agones", "--agones-port", std::to_string(sidecar.port()), "--max-matches", "8", "--mode", "asteroids"});
    // Ready, the default match counted, the watch open.
    REQUIRE(fake_sdk_server::wait_until(
        [&] { return sidecar.state() == "Ready" && sidecar.rooms() == 1 && sidecar.watchers() == 1; }, 5s));

    REQUIRE(sidecar.allocate("sandbox", "e2e-finals"));
    REQUIRE(server.log_shows("match created id=e2e-finals mode=sandbox", 5000ms));

    test_client player(server.port());
    protocol::hello_msg hello;
    hello.protocol_version = protocol::protocol_version;
    hello.name = "ann";
    hello.match = "e2e-finals";
    player.send_frame(protocol::encode_hello(hello));
    const auto frame = player.read_until(protocol::Payload::Welcome, 3000ms);
    REQUIRE(frame);
    const auto welcome = protocol::decode_welcome(*test::message_of(*frame));
    REQUIRE(welcome);
    CHECK(welcome.value.match == "e2e-finals");
    CHECK(welcome.value.mode == "sandbox");

    // The player is in the List; rooms is the two matches, not three.
    REQUIRE(
        fake_sdk_server::wait_until([&] { return sidecar.players() == std::vector<std::string>{"e2e-finals/1"}; }, 5s));
    std::this_thread::sleep_for(300ms);
    CHECK(sidecar.rooms() == 2);
    for (const auto& c : sidecar.calls())
        if (c.method == "PATCH") CHECK(c.body == R"({"countDiff":"1"})");  // the default match's, only
    CHECK(sidecar.count("PATCH", "/v1beta1/counters/rooms") == 1);

    CHECK(server.stop(SIGTERM) == 0);
    CHECK(sidecar.count("POST", "/shutdown") == 1);
}
