// arena-server's HTTP port (--http-port) against hostile or careless HTTP clients, over loopback:
// downloads that never read, /recording and /metrics kept off the public port, files in
// chunks at a bounded rate, and the upgrade request's own edge cases.
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <catch2/catch.hpp>
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

void join(ws_client& c, const std::string& name = "http-tester") {
    REQUIRE(c.open());
    REQUIRE(c.send_binary(protocol::encode_hello(protocol::protocol_version, name, "")));
    REQUIRE(c.read_until(Payload::Welcome, 3000ms));
}

std::string get(uint16_t port, const std::string& path, const std::string& headers = "",
                std::chrono::milliseconds timeout = 3000ms) {
    return raw_http(port, "GET " + path + " HTTP/1.1\r\nHost: x\r\n" + headers + "\r\n", timeout);
}

// The metrics port, from the log line "metrics on http://HOST:PORT/metrics".
uint16_t metrics_port_of(server_process& p) {
    const std::string marker = "metrics on http://";
    REQUIRE(p.log_shows(marker));
    const std::string log = p.log();
    const size_t colon = log.find(':', log.find(marker) + marker.size());
    return static_cast<uint16_t>(std::stoi(log.substr(colon + 1)));
}

std::string body_of(const std::string& answer) {
    const size_t at = answer.find("\r\n\r\n");
    return at == std::string::npos ? std::string() : answer.substr(at + 4);
}

// A file of `bytes` bytes under a fresh web root (removed with it).
struct big_file_root {
    std::filesystem::path root;
    big_file_root(size_t bytes, const std::string& tag) {
        root = std::filesystem::temp_directory_path() / ("arena-web-" + tag + "-" + std::to_string(::getpid()));
        std::filesystem::create_directories(root);
        std::ofstream out(root / "big.bin", std::ios::binary);
        const std::string block(1 << 20, 'b');
        for (size_t n = 0; n < bytes; n += block.size()) out.write(block.data(), std::min(block.size(), bytes - n));
    }
    ~big_file_root() { std::filesystem::remove_all(root); }
};

int connect_to(uint16_t port, int receive_buffer = 0) {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    if (receive_buffer > 0) ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &receive_buffer, sizeof receive_buffer);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(port);
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
        ::close(fd);
        return -1;
    }
    return fd;
}

// A socket that asks for `path` and never reads the answer (a 4 KiB receive buffer).
int stalled_get(uint16_t port, const std::string& path) {
    const int fd = connect_to(port, 4096);
    const std::string request = "GET " + path + " HTTP/1.1\r\nHost: x\r\n\r\n";
    if (fd >= 0) (void)::send(fd, request.data(), request.size(), MSG_NOSIGNAL);
    return fd;
}

}  // namespace

TEST_CASE("downloads that never read cannot keep /healthz or a WebSocket player out", "[net][ws][http]") {
    big_file_root web(16 << 20, "slow");
    http_server s({"--web-root", web.root.string()});
    std::vector<int> stalled;
    for (int i = 0; i < 80; ++i) stalled.push_back(stalled_get(s.http_port, "/big.bin"));
    std::this_thread::sleep_for(500ms);  // every one is being answered (or was turned away)
    int healthy = 0;
    for (int i = 0; i < 10; ++i)
        if (get(s.http_port, "/healthz").find("HTTP/1.1 200") == 0) ++healthy;
    CHECK(healthy == 10);
    ws_client c(s.http_port);
    join(c);
    // A page load still gets its file, at the expense of the slowest stalled one.
    const std::string file = get(s.http_port, "/big.bin", "", 30000ms);
    CHECK(file.find("HTTP/1.1 200") == 0);
    CHECK(body_of(file).size() == (16u << 20));
    CHECK(s.process.log_shows("download ended to make room"));
    for (int fd : stalled) ::close(fd);
}

TEST_CASE("a download slower than the minimum transfer rate is dropped", "[net][ws][http]") {
    big_file_root web(16 << 20, "rate");
    http_server s({"--web-root", web.root.string()});
    const int fd = stalled_get(s.http_port, "/big.bin");
    REQUIRE(fd >= 0);
    // 64 KiB at 16 KiB/s: the first chunk the kernel cannot take is given up within 4 s.
    CHECK(s.process.log_shows("download ended: slower than 16 KiB/s", 10000ms));
    ::close(fd);
}

TEST_CASE("files go out at a bounded rate, in chunks, not as fast as the game's thread can read", "[net][ws][http]") {
    // 128 MiB at 32 MiB/s for every download together: about 4 s. Before the bound, loopback
    // took 0.44 s for 100 MB, the game's thread writing all the while.
    big_file_root web(128 << 20, "pace");
    http_server s({"--web-root", web.root.string()});
    const auto start = std::chrono::steady_clock::now();
    const int fd = connect_to(s.http_port);
    REQUIRE(fd >= 0);
    const std::string request = "GET /big.bin HTTP/1.1\r\nHost: x\r\n\r\n";
    REQUIRE(::send(fd, request.data(), request.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(request.size()));
    timeval wait{20, 0};
    ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &wait, sizeof wait);
    std::vector<char> buffer(1 << 20);
    size_t received = 0;
    for (ssize_t n; (n = ::recv(fd, buffer.data(), buffer.size(), 0)) > 0;) received += static_cast<size_t>(n);
    ::close(fd);
    const auto took = std::chrono::steady_clock::now() - start;
    CHECK(received > (128u << 20));  // the file and its head
    CHECK(took >= 3000ms);
}

TEST_CASE("a single Range gets 206 or 416, several are ignored", "[net][ws][http]") {
    big_file_root web(1000, "range");
    http_server s({"--web-root", web.root.string()});
    const std::string part = get(s.http_port, "/big.bin", "Range: bytes=10-19\r\n");
    CHECK(part.find("HTTP/1.1 206") == 0);
    CHECK(part.find("Content-Range: bytes 10-19/1000") != std::string::npos);
    CHECK(body_of(part) == std::string(10, 'b'));
    CHECK(body_of(get(s.http_port, "/big.bin", "Range: bytes=-5\r\n")).size() == 5);
    const std::string beyond = get(s.http_port, "/big.bin", "Range: bytes=1000-\r\n");
    CHECK(beyond.find("HTTP/1.1 416") == 0);
    CHECK(beyond.find("Content-Range: bytes */1000") != std::string::npos);
    const std::string several = get(s.http_port, "/big.bin", "Range: bytes=0-1,5-6\r\n");
    CHECK(several.find("HTTP/1.1 200") == 0);
    CHECK(body_of(several).size() == 1000);
}

TEST_CASE("/recording is served only with --serve-recording, and then on the metrics port while the match runs",
          "[net][ws][http][replay]") {
    const auto recording =
        std::filesystem::temp_directory_path() / ("arena-served-" + std::to_string(::getpid()) + ".arpl");
    {
        http_server s({"--record", recording.string(), "--metrics-port", "0"});
        const uint16_t metrics = metrics_port_of(s.process);
        CHECK(get(s.http_port, "/recording").find("HTTP/1.1 404") == 0);
        CHECK(get(metrics, "/recording").find("HTTP/1.1 404") == 0);
    }
    http_server s({"--record", recording.string(), "--metrics-port", "0", "--serve-recording"});
    const uint16_t metrics = metrics_port_of(s.process);
    const std::string public_answer = get(s.http_port, "/recording");
    CHECK(public_answer.find("HTTP/1.1 404") == 0);
    CHECK(public_answer.find("metrics port") != std::string::npos);
    const std::string answer = get(metrics, "/recording");
    CHECK(answer.find("HTTP/1.1 200") == 0);
    CHECK(answer.find("Access-Control-Allow-Origin: *") != std::string::npos);
    CHECK(body_of(answer).substr(8, 4) == "ARPL");  // a length, a root offset, the identifier
    const std::string part = get(metrics, "/recording", "Range: bytes=8-11\r\n");
    CHECK(part.find("HTTP/1.1 206") == 0);
    CHECK(body_of(part) == "ARPL");
    std::filesystem::remove(recording);
}

TEST_CASE("with --metrics-port, /metrics is not served on the HTTP port", "[net][ws][http]") {
    {
        http_server open({});
        CHECK(get(open.http_port, "/metrics").find("HTTP/1.1 200") == 0);
    }
    http_server s({"--metrics-port", "0", "--metrics-bind", "127.0.0.1"});
    CHECK(get(s.http_port, "/metrics").find("HTTP/1.1 404") == 0);
    CHECK(get(s.http_port, "/healthz").find("HTTP/1.1 200") == 0);
    CHECK(get(metrics_port_of(s.process), "/metrics").find("HTTP/1.1 200") == 0);
}

TEST_CASE("HEAD /healthz is answered like GET without a body", "[net][ws][http]") {
    http_server s({});
    const std::string head = raw_http(s.http_port, "HEAD /healthz HTTP/1.1\r\nHost: x\r\n\r\n");
    CHECK(head.find("HTTP/1.1 200") == 0);
    CHECK(head.find("Content-Length: 3") != std::string::npos);
    CHECK(body_of(head).empty());
}

TEST_CASE("a request that announces a body gets 400 at once, not silence until the head timeout", "[net][ws][http]") {
    http_server s({"--handshake-timeout", "10"});
    const std::string answer = get(s.http_port, "/healthz", "Transfer-Encoding: chunked\r\n", 3000ms);
    CHECK(answer.find("HTTP/1.1 400") == 0);
}

TEST_CASE("an upgrade whose Sec-WebSocket-Key is not the base64 of 16 bytes gets 400", "[net][ws][http]") {
    http_server s({});
    const std::string head =
        "GET /ws HTTP/1.1\r\nHost: x\r\nUpgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Version: "
        "13\r\nSec-WebSocket-Key: ";
    CHECK(raw_http(s.http_port, head + "!!!!\r\n\r\n").find("HTTP/1.1 400") == 0);
    CHECK(raw_http(s.http_port, head + "dGhlIHNhbXBsZSBub25jZQ==\r\n\r\n", 500ms).find("HTTP/1.1 101") == 0);
}

TEST_CASE("a WebSocket frame sent in the same write as the upgrade is read, not dropped", "[net][ws][http]") {
    http_server s({"--handshake-timeout", "10"});
    const int fd = connect_to(s.http_port);
    REQUIRE(fd >= 0);
    std::string bytes =
        "GET /ws HTTP/1.1\r\nHost: x\r\nUpgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Version: "
        "13\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n\r\n";
    // A client's frame is masked: FIN + binary, the mask bit and the length, a zero mask.
    const protocol::frame_bytes hello = protocol::encode_hello(protocol::protocol_version, "eager", "");
    REQUIRE(hello.size() < 126);
    bytes += {char(0x82), char(0x80 | hello.size()), 0, 0, 0, 0};
    bytes.append(reinterpret_cast<const char*>(hello.data()), hello.size());
    REQUIRE(::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(bytes.size()));
    // The 101, then the server's first frame: the Welcome (before the fix, nothing until a
    // Reject for want of a Hello at the handshake timeout).
    timeval wait{3, 0};
    ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &wait, sizeof wait);
    std::string in;
    std::optional<protocol::Payload> first;
    char buffer[65536];
    for (ssize_t n; !first && (n = ::recv(fd, buffer, sizeof buffer, 0)) > 0;) {
        in.append(buffer, static_cast<size_t>(n));
        const size_t head_end = in.find("\r\n\r\n");
        if (head_end == std::string::npos || in.size() < head_end + 6) continue;
        const auto* f = reinterpret_cast<const uint8_t*>(in.data() + head_end + 4);
        size_t length = f[1] & 0x7f, at = 2;
        if (length == 126) length = size_t{f[2]} << 8 | f[3], at = 4;
        if (length == 127) continue;  // not a Welcome's size
        if (in.size() < head_end + 4 + at + length) continue;
        const std::vector<uint8_t> frame(f + at, f + at + length);
        if (const protocol::Message* m = message_of(frame)) first = m->payload_type();
    }
    ::close(fd);
    CHECK(in.find("HTTP/1.1 101") == 0);
    REQUIRE(first);
    CHECK(*first == Payload::Welcome);
}

TEST_CASE("by default only the server's own page (or a program, without Origin) may open /ws", "[net][ws][http]") {
    {
        http_server s({});
        ws_client other(s.http_port, "https://evil.example.net");
        CHECK_FALSE(other.open());
        CHECK(other.refused_status() == 403);
        ws_client own(s.http_port, "http://127.0.0.1:" + std::to_string(s.http_port));
        join(own, "own");
        ws_client program(s.http_port);
        join(program, "program");
    }
    http_server any({"--allowed-origin", "*"});
    ws_client other(any.http_port, "https://evil.example.net");
    join(other, "other");
}
