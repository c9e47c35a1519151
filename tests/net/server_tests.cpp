// arena-server end to end over loopback, with real sockets.
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

TEST_CASE("a client joins, sends inputs and receives snapshots that follow them", "[net][e2e]") {
    server_process server({"--preset", "asteroids"});
    joined_client c(server.port());
    CHECK(c.welcome.tick_rate == 60);
    CHECK(c.welcome.snapshot_rate == 20);
    CHECK(c.welcome.preset == "asteroids");

    std::vector<uint32_t> ticks, acks;
    const protocol::BodyState* own = nullptr;
    std::vector<uint8_t> last_snapshot;
    uint32_t sequence = 0;
    const auto start = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - start < 1500ms) {
        c.client.send_frame(protocol::encode_input({++sequence, 1.0f, 0.0f, 0}));
        const auto next = start + sequence * 16667us;
        while (std::chrono::steady_clock::now() < next) {
            auto frame = c.client.read_frame(
                std::chrono::duration_cast<std::chrono::milliseconds>(next - std::chrono::steady_clock::now()) + 1ms);
            if (!frame) continue;
            const protocol::Message* m = message_of(*frame);
            REQUIRE(m);
            if (m->payload_type() != Payload::Snapshot) continue;
            auto snap = protocol::decode_snapshot(*m);
            REQUIRE(snap);
            ticks.push_back(snap.value.tick);
            acks.push_back(snap.value.ack_sequence);
            last_snapshot = *frame;
        }
    }
    REQUIRE(ticks.size() >= 20);
    // Every third tick at 60/20. A server that stalls catches up several ticks at once, and
    // the newer snapshot replaces one not yet sent (one snapshot slot per client): a gap of a
    // multiple of 3 is allowed, rarely.
    size_t regular = 0;
    for (size_t i = 1; i < ticks.size(); ++i) {
        CHECK(ticks[i] > ticks[i - 1]);
        CHECK((ticks[i] - ticks[i - 1]) % 3 == 0);
        regular += ticks[i] == ticks[i - 1] + 3 ? 1 : 0;
        CHECK(acks[i] >= acks[i - 1]);
    }
    CHECK(regular * 10 >= (ticks.size() - 1) * 9);
    CHECK(acks.back() > 0);
    CHECK(acks.back() <= sequence);
    auto snap = protocol::decode_snapshot(*message_of(last_snapshot));
    for (const auto& b : snap.value.bodies)
        if (b.id() == c.welcome.entity_id) own = &b;
    REQUIRE(own);
    CHECK(own->owner() == c.welcome.player_id);
    // Full thrust along the facing (angle 0, no turn): the body speeds up along +x.
    CHECK(own->vx() > 5.0f);
    CHECK(std::fabs(own->vy()) < 0.5f);
    CHECK(own->angle() == 0.0f);
}

TEST_CASE("ping is answered with pong", "[net][e2e]") {
    server_process server({});
    joined_client c(server.port());
    c.client.send_frame(protocol::encode_ping(123456789));
    auto frame = c.client.read_until(Payload::Pong);
    REQUIRE(frame);
    auto pong = protocol::decode_pong(*message_of(*frame));
    REQUIRE(pong);
    CHECK(pong.value.client_time == 123456789);
    // How long the Ping waited in the kernel for the tick's read: the server reads once a tick
    // (16.7 ms), so at most about one tick; a generous bound for a loaded machine.
    REQUIRE(pong.value.server_hold_us.has_value());
    CHECK(*pong.value.server_hold_us < 1'000'000);
}

TEST_CASE("a Ping that waited for the tick's read is answered with the time it waited", "[net][e2e]") {
    // The bots measured 17 ms of round trip on loopback: the wait for the server's next read.
    // Sent right after a snapshot (just after a tick's read), a Ping waits most of a tick.
    server_process server({});
    joined_client c(server.port());
    uint32_t longest_us = 0;
    for (int k = 0; k < 5; ++k) {
        REQUIRE(c.client.read_until(Payload::Snapshot));
        c.client.send_frame(protocol::encode_ping(k + 1));
        auto frame = c.client.read_until(Payload::Pong);
        REQUIRE(frame);
        auto pong = protocol::decode_pong(*message_of(*frame));
        REQUIRE(pong);
        REQUIRE(pong.value.server_hold_us.has_value());
        longest_us = std::max(longest_us, *pong.value.server_hold_us);
    }
    CHECK(longest_us > 1000);  // a millisecond: more than a read that answered at once
}

TEST_CASE("a spectator over TCP watches the full match's bodies and its Input is refused", "[net][e2e][spectator]") {
    server_process server({"--preset", "asteroids", "--max-players", "1", "--max-spectators", "1"});
    joined_client player(server.port(), "player");
    test_client eye(server.port());
    eye.send_frame(protocol::encode_hello(protocol::protocol_version, "player", "", false, true));
    auto frame = eye.read_until(Payload::Welcome);
    REQUIRE(frame);
    auto welcome = protocol::decode_welcome(*message_of(*frame));
    REQUIRE(welcome);
    CHECK(welcome.value.entity_id == 0);
    CHECK(welcome.value.player_id != player.welcome.player_id);
    // The player's ship, in a snapshot of the spectator's, and no body of its own.
    bool seen = false;
    for (int i = 0; i < 40 && !seen; ++i) {
        frame = eye.read_until(Payload::Snapshot);
        REQUIRE(frame);
        auto snapshot = protocol::decode_snapshot(*message_of(*frame));
        REQUIRE(snapshot);
        for (const protocol::BodyState& b : snapshot.value.bodies) {
            CHECK(b.owner() != welcome.value.player_id);
            seen = seen || b.owner() == player.welcome.player_id;
        }
    }
    CHECK(seen);
    {
        test_client second(server.port());  // the one spectator slot is taken
        second.send_frame(protocol::encode_hello(protocol::protocol_version, "two", "", false, true));
        CHECK(expect_reject(second).code == protocol::RejectCode::server_full);
    }
    eye.send_frame(protocol::encode_input({1, 1.0f, 0.0f, 0}));
    const protocol::reject_msg no = expect_reject(eye);
    CHECK(no.code == protocol::RejectCode::bad_request);
    CHECK(no.reason == "Input from a spectator, who has no body");
    // The player plays on.
    player.client.send_frame(protocol::encode_input({1, 1.0f, 0.0f, 0}));
    CHECK(count_snapshots(player.client, 300ms) > 0);
}
TEST_CASE("SIGTERM says bye to every client, writes the stats and exits 0", "[net][e2e]") {
    const std::string stats = temp_path("stats.json");
    server_process server({"--stats-json", stats});
    joined_client c(server.port());
    count_snapshots(c.client, 300ms);
    ::kill(server.pid(), SIGTERM);
    auto bye = c.client.read_until(Payload::Bye);
    REQUIRE(bye);
    CHECK(protocol::decode_bye(*message_of(*bye)).value.reason.find("SIGTERM") != std::string::npos);
    CHECK(server.stop(0) == 0);
    const std::string text = read_file(stats);
    CHECK(text.find("\"ticks\"") != std::string::npos);
    CHECK(text.find("\"joins\": 1") != std::string::npos);
    std::remove(stats.c_str());
}

TEST_CASE("a match with a duration ends cleanly", "[net][e2e]") {
    server_process server({"--duration", "0.5"});
    joined_client c(server.port());
    auto bye = c.client.read_until(Payload::Bye, 3000ms);
    REQUIRE(bye);
    CHECK(server.stop(0, 3000ms) == 0);
}

TEST_CASE("a client still sending inputs when the match ends reads the Bye and then a clean end instead of a reset",
          "[net][e2e]") {
    // The server reads inputs only at ticks, so the ones sent as the match ends stay unread.
    // Closing over them used to make the kernel reset the connection: the client's next write
    // failed, and a client that wrote before it read ended on that error, the Bye unseen.
    server_process server({"--duration", "0.5"});
    joined_client c(server.port());
    uint32_t sequence = 0;
    std::optional<std::vector<uint8_t>> bye;
    const auto give_up = std::chrono::steady_clock::now() + 5s;
    while (!bye && std::chrono::steady_clock::now() < give_up) {
        c.client.send_frame(protocol::encode_input({++sequence, 1.0f, 0.0f, 0}));
        auto frame = c.client.read_frame(5ms);
        if (frame && message_of(*frame) && message_of(*frame)->payload_type() == Payload::Bye) bye = frame;
    }
    REQUIRE(bye);
    // Inputs keep going out after the Bye, as from a client that has not read it yet.
    int sent_whole = 0;
    for (int i = 0; i < 20; ++i) {
        const protocol::frame_bytes input = protocol::encode_input({++sequence, 1.0f, 0.0f, 0});
        if (::send(c.client.fd(), input.data(), input.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(input.size()))
            ++sent_whole;
        std::this_thread::sleep_for(10ms);
    }
    CHECK(sent_whole == 20);
    ::shutdown(c.client.fd(), SHUT_WR);
    pollfd p{c.client.fd(), POLLIN, 0};
    REQUIRE(::poll(&p, 1, 3000) == 1);
    uint8_t rest[4096];
    const ssize_t n = ::recv(c.client.fd(), rest, sizeof rest, 0);
    INFO("recv: " << (n < 0 ? std::strerror(errno) : std::to_string(n) + " bytes"));
    CHECK(n == 0);
    CHECK(server.stop(0, 3000ms) == 0);
}

TEST_CASE("with --token-secret only signed, unexpired tokens join, under the signed name", "[net][e2e][auth]") {
    const std::string secret = temp_path("secret");
    std::ofstream(secret) << "0123456789abcdef0123456789abcdef-test-secret";
    server_process server({"--token-secret", secret});
    {
        test_client c(server.port());
        c.send_frame(protocol::encode_hello(protocol::protocol_version, "mallory", "not-a-token"));
        CHECK(expect_reject(c).code == protocol::RejectCode::unauthorized);
    }
    // arena-token mints a token the server accepts.
    const auto minted = run_command(program("arena-token") + " --secret " + secret + " --name alice --ttl 60");
    REQUIRE(minted.exit_code == 0);
    std::string token = minted.output;
    token.erase(token.find_last_not_of("\n") + 1);
    test_client c(server.port());
    c.send_frame(protocol::encode_hello(protocol::protocol_version, "claims-to-be-bob", token));
    REQUIRE(c.read_until(Payload::Welcome));
    CHECK(server.log_shows("name=alice"));
    std::remove(secret.c_str());
}

TEST_CASE("a player whose connection drops reconnects to the same body with its token", "[net][e2e][reconnect]") {
    server_process server({"--reconnect-grace", "5"});
    protocol::welcome_info first;
    {
        test_client c(server.port());
        c.send_frame(protocol::encode_hello(protocol::protocol_version, "wanderer", "my-session-key"));
        auto frame = c.read_until(Payload::Welcome);
        REQUIRE(frame);
        first = protocol::decode_welcome(*message_of(*frame)).value;
    }  // the socket closes without a Bye
    std::this_thread::sleep_for(200ms);
    test_client again(server.port());
    again.send_frame(protocol::encode_hello(protocol::protocol_version, "wanderer", "my-session-key"));
    auto frame = again.read_until(Payload::Welcome);
    REQUIRE(frame);
    const auto second = protocol::decode_welcome(*message_of(*frame)).value;
    CHECK(second.player_id == first.player_id);
    CHECK(second.entity_id == first.entity_id);
    CHECK(count_snapshots(again, 500ms) >= 8);
}

TEST_CASE("a recorded live session replays with every hash matching", "[net][e2e][replay]") {
    const std::string recording = temp_path("session.arpl");
    server_process server({"--record", recording, "--hash-interval", "10"});
    {
        joined_client a(server.port(), "a");
        joined_client b(server.port(), "b");
        for (uint32_t s = 1; s <= 90; ++s) {
            a.client.send_frame(protocol::encode_input({s, 1.0f, 0.3f, static_cast<uint8_t>(s % 20 == 0)}));
            b.client.send_frame(protocol::encode_input({s, -0.5f, -1.0f, 0}));
            std::this_thread::sleep_for(16ms);
        }
        b.client.send_frame(protocol::encode_bye("leaving early"));
        std::this_thread::sleep_for(200ms);
    }
    REQUIRE(server.stop(SIGTERM) == 0);
    const auto replayed = run_command(program("arena-replay") + " " + recording + " 2>&1");
    INFO(replayed.output);
    CHECK(replayed.exit_code == 0);
    CHECK(replayed.output.find("final_hash=") != std::string::npos);
    CHECK(server.log_shows("recorded "));
    std::remove(recording.c_str());
}
