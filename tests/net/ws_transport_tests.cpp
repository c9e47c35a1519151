// arena-server's HTTP port (--http-port) end to end over loopback: the game over WebSocket at
// /ws beside TCP (server/net/web_transport.*, ws_session.*), the same admission and Reject codes
// as TCP, WebSocket's own abuse, the ops routes and the static files on the same port.
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>

#include "protocol/decode.hpp"
#include "protocol/version.hpp"
#include "server_process.hpp"
#include "ws_client.hpp"

using namespace arena;
using namespace arena::test;
using namespace std::chrono_literals;
using protocol::Payload;

namespace {

protocol::welcome_info join(ws_client& c, const std::string& name = "ws-tester") {
    REQUIRE(c.open());
    REQUIRE(c.send_binary(protocol::encode_hello(protocol::protocol_version, name, "")));
    auto welcome = c.read_until(Payload::Welcome, 3000ms);
    REQUIRE(welcome);
    auto w = protocol::decode_welcome(*message_of(*welcome));
    REQUIRE(w);
    return w.value;
}

protocol::reject_msg expect_reject(ws_client& c) {
    auto frame = c.read_until(Payload::Reject, 4000ms);
    REQUIRE(frame);
    auto r = protocol::decode_reject(*message_of(*frame));
    REQUIRE(r);
    return r.value;
}

// The position of body `id` in a snapshot message, if it is in it.
std::optional<std::pair<float, float>> position_of(const std::vector<uint8_t>& frame, uint32_t id) {
    const protocol::Message* m = message_of(frame);
    if (m == nullptr || m->payload_type() != Payload::Snapshot) return std::nullopt;
    auto s = protocol::decode_snapshot(*m);
    if (!s) return std::nullopt;
    for (const protocol::BodyState& b : s.value.bodies)
        if (b.id() == id) return std::pair{b.x(), b.y()};
    return std::nullopt;
}

// A joined client that keeps receiving snapshots for `duration` (another client's trouble
// must not stop them).
int snapshots_within(ws_client& c, std::chrono::milliseconds duration) {
    int n = 0;
    const auto end = std::chrono::steady_clock::now() + duration;
    uint32_t sequence = 1;
    while (std::chrono::steady_clock::now() < end) {
        c.send_binary(protocol::encode_input({sequence++, 0.0f, 0.0f, 0}));
        if (auto m = c.read_message(20ms); m && message_of(*m) && message_of(*m)->payload_type() == Payload::Snapshot)
            ++n;
    }
    return n;
}

}  // namespace

TEST_CASE("a WebSocket client joins over /ws beside TCP, gets snapshots, and its inputs move its ship", "[net][ws]") {
    http_server s({});
    test_client tcp(s.process.port());
    tcp.send_frame(protocol::encode_hello(protocol::protocol_version, "tcp-player", ""));
    REQUIRE(tcp.read_until(Payload::Welcome));

    ws_client c(s.http_port);
    const protocol::welcome_info welcome = join(c);
    std::optional<std::pair<float, float>> first, last;
    uint32_t max_ack = 0;
    uint32_t sequence = 1;
    const auto start = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - start < 1500ms) {
        REQUIRE(c.send_binary(protocol::encode_input({sequence++, 1.0f, 0.0f, 0})));
        const auto next = start + sequence * 16667us;
        while (std::chrono::steady_clock::now() < next) {
            auto m = c.read_message(2ms);
            if (!m) continue;
            if (auto p = position_of(*m, welcome.entity_id)) {
                if (!first) first = p;
                last = p;
                max_ack = std::max(max_ack, protocol::decode_snapshot(*message_of(*m)).value.ack_sequence);
            }
        }
    }
    REQUIRE(first);
    REQUIRE(last);
    const double moved = std::hypot(last->first - first->first, last->second - first->second);
    CHECK(moved > 1.0);   // thrust for 1.5 s moves the ship metres
    CHECK(max_ack > 30);  // the server consumed our inputs and acknowledges them
    // Counted with TCP's connections, on the same port's /metrics.
    const std::string metrics = raw_http(s.http_port, "GET /metrics HTTP/1.1\r\nHost: x\r\n\r\n");
    CHECK(metrics.find("HTTP/1.1 200") == 0);
    CHECK(metrics.find("arena_connections_open 2\n") != std::string::npos);
    CHECK(raw_http(s.http_port, "GET /healthz HTTP/1.1\r\nHost: x\r\n\r\n").find("HTTP/1.1 200") == 0);
    CHECK(s.process.log_shows("hello player="));
}

TEST_CASE("malformed WebSocket messages get TCP's Reject codes and only their connection ends", "[net][ws]") {
    http_server s({});
    ws_client honest(s.http_port);
    join(honest, "honest");

    SECTION("bytes that are no FlatBuffers message") {
        ws_client bad(s.http_port);
        REQUIRE(bad.open());
        bad.send_binary({8, 0, 0, 0, 0xde, 0xad, 0xbe, 0xef, 1, 2, 3, 4});
        CHECK(expect_reject(bad).code == protocol::RejectCode::bad_request);
        CHECK(bad.closed_by_peer());
        CHECK(s.process.log_shows("code=bad_request reason=frame failed verification"));
    }
    SECTION("a length prefix over the frame limit, refused by the prefix") {
        ws_client bad(s.http_port);
        REQUIRE(bad.open());
        bad.send_binary({0, 0, 0x10, 0, 1, 2, 3});  // 1 MiB claimed
        CHECK(expect_reject(bad).code == protocol::RejectCode::too_large);
        CHECK(bad.closed_by_peer());
    }
    SECTION("two frames in one message") {
        ws_client bad(s.http_port);
        REQUIRE(bad.open());
        auto two = protocol::encode_hello(protocol::protocol_version, "two", "");
        const auto second = protocol::encode_ping(1);
        two.insert(two.end(), second.begin(), second.end());
        bad.send_binary(two);
        CHECK(expect_reject(bad).code == protocol::RejectCode::bad_request);
        CHECK(s.process.log_shows("more than one frame"));
    }
    SECTION("a message that ends inside its frame") {
        ws_client bad(s.http_port);
        REQUIRE(bad.open());
        auto hello = protocol::encode_hello(protocol::protocol_version, "cut", "");
        hello.resize(hello.size() - 3);
        bad.send_binary(hello);
        CHECK(expect_reject(bad).code == protocol::RejectCode::bad_request);
        CHECK(s.process.log_shows("ends inside a frame"));
    }
    SECTION("a text message") {
        ws_client bad(s.http_port);
        REQUIRE(bad.open());
        bad.send_text("{\"hello\": 1}");
        CHECK(expect_reject(bad).code == protocol::RejectCode::bad_request);
        CHECK(s.process.log_shows("a text message"));
    }
    SECTION("the wrong protocol version, as on TCP") {
        ws_client bad(s.http_port);
        REQUIRE(bad.open());
        bad.send_binary(protocol::encode_hello(protocol::protocol_version + 1, "old", ""));
        CHECK(expect_reject(bad).code == protocol::RejectCode::version_mismatch);
    }
    CHECK(snapshots_within(honest, 500ms) >= 5);
}

TEST_CASE(
    "a WebSocket message over the frame limit ends the connection before it is buffered, "
    "even in fragments",
    "[net][ws]") {
    http_server s({});
    ws_client honest(s.http_port);
    join(honest, "honest");
    ws_client big(s.http_port);
    REQUIRE(big.open());
    // A prefix that claims the largest body, then more than it in 16 KiB fragments.
    std::vector<uint8_t> bytes(80 * 1024, 0x41);
    const uint32_t body = protocol::max_client_frame_body;
    for (int i = 0; i < 4; ++i) bytes[static_cast<size_t>(i)] = static_cast<uint8_t>(body >> (8 * i));
    big.send_fragmented(bytes, 16 * 1024);
    CHECK(big.closed_by_peer());
    CHECK(s.process.log_shows("code=too_large reason=a WebSocket message over 65540 bytes"));
    CHECK(snapshots_within(honest, 500ms) >= 5);
}

TEST_CASE("an upgrade that never completes is dropped after the handshake timeout", "[net][ws]") {
    http_server s({"--handshake-timeout", "1"});
    const auto start = std::chrono::steady_clock::now();
    const std::string answer = raw_http(s.http_port, "GET /ws HTTP/1.1\r\nHost: x\r\nUpgrade: websocket\r\n", 4000ms);
    const auto waited = std::chrono::steady_clock::now() - start;
    CHECK(answer.empty());
    CHECK(waited >= 900ms);
    CHECK(waited < 3000ms);
    CHECK(s.process.log_shows("request head not complete within 1.0 s"));
    // A connection upgraded but silent is the match's: the handshake timeout (Hello) applies.
    ws_client silent(s.http_port);
    REQUIRE(silent.open());
    CHECK(expect_reject(silent).code == protocol::RejectCode::timeout);
}

TEST_CASE("with --allowed-origin, upgrades from other pages get 403", "[net][ws]") {
    http_server s({"--allowed-origin", "https://play.example.com", "--allowed-origin", "http://localhost:8080"});
    ws_client other(s.http_port, "https://evil.example.net");
    CHECK_FALSE(other.open());
    CHECK(other.refused_status() == 403);
    CHECK(s.process.log_shows("Origin 'https://evil.example.net' is not allowed"));
    ws_client none(s.http_port);
    CHECK_FALSE(none.open());
    CHECK(none.refused_status() == 403);
    ws_client good(s.http_port, "https://play.example.com");
    join(good);
    ws_client second(s.http_port, "http://localhost:8080");
    join(second, "second");
}

TEST_CASE("a WebSocket ping flood is refused with ping_limit", "[net][ws]") {
    http_server s({});
    ws_client honest(s.http_port);
    join(honest, "honest");
    ws_client flood(s.http_port);
    join(flood, "flood");
    for (int i = 0; i < 200 && flood.ping(); ++i) {
    }
    CHECK(expect_reject(flood).code == protocol::RejectCode::ping_limit);
    CHECK(flood.closed_by_peer());
    CHECK(s.process.log_shows("code=ping_limit reason=more than 10 WebSocket pings a second"));
    CHECK(snapshots_within(honest, 500ms) >= 5);
}

TEST_CASE("the HTTP port serves files under --web-root only, with their content types", "[net][ws][http]") {
    const auto root = std::filesystem::temp_directory_path() / ("arena-web-" + std::to_string(::getpid()));
    std::filesystem::create_directories(root / "sub");
    std::ofstream(root / "index.html") << "<p>arena</p>";
    std::ofstream(root / "sub" / "app.wasm") << "\0asm";
    std::ofstream(root / ".secret") << "hidden";
    const auto outside = root.parent_path() / ("arena-web-outside-" + std::to_string(::getpid()));
    std::ofstream(outside) << "outside";
    std::filesystem::create_symlink(outside, root / "link.txt");
    http_server s({"--web-root", root.string()});
    auto get = [&](const std::string& path) {
        return raw_http(s.http_port, "GET " + path + " HTTP/1.1\r\nHost: x\r\n\r\n");
    };
    const std::string index = get("/");
    CHECK(index.find("HTTP/1.1 200") == 0);
    CHECK(index.find("Content-Type: text/html; charset=utf-8") != std::string::npos);
    CHECK(index.find("<p>arena</p>") != std::string::npos);
    CHECK(get("/sub/app.wasm").find("Content-Type: application/wasm") != std::string::npos);
    const std::string name = outside.filename().string();
    for (const std::string& path : std::vector<std::string>{"/../" + name, "/sub/../../" + name, "/%2e%2e/" + name,
                                                            "/.secret", "/link.txt", "/missing.js"}) {
        INFO(path);
        const std::string answer = get(path);
        CHECK(answer.find("HTTP/1.1 404") == 0);
        CHECK(answer.find("outside") == std::string::npos);
        CHECK(answer.find("hidden") == std::string::npos);
    }
    CHECK(s.process.log_shows("resolves outside the web root"));
    CHECK(raw_http(s.http_port, "POST / HTTP/1.1\r\nHost: x\r\n\r\n").find("HTTP/1.1 405") == 0);
    CHECK(get("/ws").find("HTTP/1.1 426") == 0);
    std::filesystem::remove_all(root);
    std::filesystem::remove(outside);
}

TEST_CASE("/recording serves the --record file as far as it is written, and is a 404 without one",
          "[net][ws][http][replay]") {
    const auto recording =
        std::filesystem::temp_directory_path() / ("arena-recording-" + std::to_string(::getpid()) + ".arpl");
    {
        http_server bare({});
        const std::string answer = raw_http(bare.http_port, "GET /recording HTTP/1.1\r\nHost: x\r\n\r\n");
        CHECK(answer.find("HTTP/1.1 404") == 0);
        CHECK(answer.find("--record") != std::string::npos);
    }
    // While the match runs, on the metrics port only, and only when asked for (http_port_tests.cpp).
    http_server s({"--record", recording.string(), "--serve-recording", "--metrics-port", "0"});
    const std::string marker = "metrics on http://";
    REQUIRE(s.process.log_shows(marker));
    const std::string log = s.process.log();
    const auto metrics_port =
        static_cast<uint16_t>(std::stoi(log.substr(log.find(':', log.find(marker) + marker.size()) + 1)));
    // The header is written when the recorder opens; the answer is the file's bytes then.
    const std::string answer = raw_http(metrics_port, "GET /recording HTTP/1.1\r\nHost: x\r\n\r\n");
    CHECK(answer.find("HTTP/1.1 200") == 0);
    CHECK(answer.find("Content-Type: application/octet-stream") != std::string::npos);
    const size_t body = answer.find("\r\n\r\n");
    REQUIRE(body != std::string::npos);
    // Every recording starts with a length, a root offset and the identifier ARPL.
    CHECK(answer.substr(body + 4 + 8, 4) == "ARPL");
    const std::string head = raw_http(metrics_port, "HEAD /recording HTTP/1.1\r\nHost: x\r\n\r\n");
    CHECK(head.find("HTTP/1.1 200") == 0);
    CHECK(head.find("ARPL") == std::string::npos);
    std::filesystem::remove(recording);
}

TEST_CASE("at shutdown a WebSocket client reads its Bye, and the server waits for it", "[net][ws]") {
    http_server s({});
    ws_client c(s.http_port);
    join(c);
    REQUIRE(::kill(s.process.pid(), SIGTERM) == 0);
    auto bye = c.read_until(Payload::Bye, 3000ms);
    REQUIRE(bye);
    auto b = protocol::decode_bye(*message_of(*bye));
    REQUIRE(b);
    CHECK(b.value.reason.find("SIGTERM") != std::string::npos);
    CHECK(c.closed_by_peer());
    // It exits by itself: a second SIGTERM could find it past its handlers, killed by the signal.
    CHECK(s.process.stop(0) == 0);
}

TEST_CASE("idle HTTP connections cannot keep /healthz or a WebSocket player out", "[net][ws][http]") {
    http_server s({});
    std::vector<int> idle;
    for (int i = 0; i < 80; ++i) {
        const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
        sockaddr_in address{};
        address.sin_family = AF_INET;
        address.sin_port = htons(s.http_port);
        address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        REQUIRE(::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0);
        idle.push_back(fd);
    }
    std::this_thread::sleep_for(100ms);
    CHECK(raw_http(s.http_port, "GET /healthz HTTP/1.1\r\nHost: x\r\n\r\n").find("HTTP/1.1 200") == 0);
    ws_client c(s.http_port);
    join(c);
    for (int fd : idle) ::close(fd);
}

TEST_CASE("a WebSocket client that never reads is dropped as slow_consumer, and the others play on", "[net][ws]") {
    // As the TCP test: 1000 rocks make each whole-world snapshot about 32 KB; a 4 KiB receive
    // buffer on the sleeper and 64 KiB of send buffer on the server fill within a second.
    const auto config =
        std::filesystem::temp_directory_path() / ("arena-ws-big-" + std::to_string(::getpid()) + ".json");
    std::ofstream(config) << R"({"preset": "asteroids", "size": [2000, 2000], "rocks": {"count": 1000}})";
    http_server s(
        {"--config", config.string(), "--stall-timeout", "1", "--socket-send-buffer", "65536", "--view-radius", "0"});
    ws_client good(s.http_port);
    join(good, "good");
    ws_client sleeper(s.http_port, "", "/ws", 4096);
    join(sleeper, "sleeper");  // and never reads again
    CHECK(snapshots_within(good, 3000ms) >= 50);
    CHECK(s.process.log_shows("code=slow_consumer reason=no progress writing to the client"));
    CHECK(snapshots_within(good, 1000ms) >= 18);
    std::filesystem::remove(config);
}
