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

using namespace arena;
using namespace arena::test;
using namespace std::chrono_literals;
using protocol::Payload;

namespace {

struct joined_client {
    test_client client;
    protocol::welcome_info welcome;
    explicit joined_client(uint16_t port, const std::string& name = "tester", int receive_buffer = 0)
        : client(port, receive_buffer) {
        client.send_frame(protocol::encode_hello(protocol::protocol_version, name, ""));
        auto frame = client.read_until(Payload::Welcome);
        REQUIRE(frame);
        auto w = protocol::decode_welcome(*message_of(*frame));
        REQUIRE(w);
        welcome = w.value;
    }
};

protocol::reject_msg expect_reject(test_client& c) {
    auto frame = c.read_until(Payload::Reject);
    REQUIRE(frame);
    auto r = protocol::decode_reject(*message_of(*frame));
    REQUIRE(r);
    CHECK(c.closed_by_peer());
    return r.value;
}

// Snapshots a client receives in `duration` while it reads everything.
int count_snapshots(test_client& c, std::chrono::milliseconds duration) {
    int count = 0;
    const auto end = std::chrono::steady_clock::now() + duration;
    while (std::chrono::steady_clock::now() < end) {
        auto frame = c.read_frame(20ms);
        if (frame && message_of(*frame) && message_of(*frame)->payload_type() == Payload::Snapshot) ++count;
    }
    return count;
}

}  // namespace

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
