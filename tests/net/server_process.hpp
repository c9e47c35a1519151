#pragma once
// Test helpers: an arena-server child process on a free loopback port, and a blocking TCP
// client that speaks the protocol. Plain POSIX, so the tests need no Asio.
#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "protocol/arena_generated.h"
#include "protocol/messages.hpp"

namespace arena::test {

class server_process {
public:
    // Starts build/bin/arena-server --port 0 with `args`, and waits for "listening on".
    explicit server_process(const std::vector<std::string>& args);
    ~server_process();
    server_process(const server_process&) = delete;
    server_process& operator=(const server_process&) = delete;

    uint16_t port() const { return port_; }
    // The port of the next stdout line "PREFIX HOST:PORT" (e.g. "udp listening on"), or 0
    // when none comes within `timeout`.
    uint16_t port_line(const std::string& prefix, std::chrono::milliseconds timeout = std::chrono::milliseconds(5000));
    pid_t pid() const { return pid_; }
    // Sends a signal and waits for the exit status (or -1 after `timeout`).
    int stop(int signal, std::chrono::milliseconds timeout = std::chrono::milliseconds(5000));
    // Resident set size in KiB, from /proc.
    long rss_kib() const;
    // Everything the server wrote to stderr so far (its log).
    std::string log();
    // Whether the log holds `text` within `timeout`: the server's line may still be on its way
    // through the pipe and the drain thread when the client has already seen the effect.
    bool log_shows(const std::string& text, std::chrono::milliseconds timeout = std::chrono::milliseconds(2000));

private:
    pid_t pid_ = -1;
    int stdout_fd_ = -1;
    int stderr_fd_ = -1;
    uint16_t port_ = 0;
    std::string log_;
    std::mutex log_mutex_;
    std::thread log_drain_;  // reads stderr all along: a full pipe would block the server
};

class test_client {
public:
    // receive_buffer > 0 shrinks the socket's receive buffer (a client that fills up fast).
    explicit test_client(uint16_t port, int receive_buffer = 0);
    ~test_client();
    test_client(const test_client&) = delete;
    test_client& operator=(const test_client&) = delete;

    void send_bytes(const std::vector<uint8_t>& bytes);
    void send_frame(const protocol::frame_bytes& frame) { send_bytes(frame); }
    // The next frame's bytes, or nothing on timeout or a closed connection.
    std::optional<std::vector<uint8_t>> read_frame(std::chrono::milliseconds timeout = std::chrono::milliseconds(3000));
    // Reads frames until one of `type` arrives (others are dropped).
    std::optional<std::vector<uint8_t>> read_until(protocol::Payload type,
                                                   std::chrono::milliseconds timeout = std::chrono::milliseconds(3000));
    // True when the server closed the connection within `timeout` (frames before are skipped).
    bool closed_by_peer(std::chrono::milliseconds timeout = std::chrono::milliseconds(3000));
    int fd() const { return fd_; }

private:
    bool fill(size_t want, std::chrono::steady_clock::time_point deadline);
    int fd_ = -1;
    std::vector<uint8_t> buffer_;
};

// arena-server with its UDP port open besides TCP (--udp-port 0), and that port.
struct udp_server {
    server_process process;
    uint16_t udp_port = 0;
    explicit udp_server(std::vector<std::string> args);
};

// arena-server with its HTTP port open (--http-port 0: the page, /ws, /healthz), and that port.
struct http_server {
    server_process process;
    uint16_t http_port = 0;
    explicit http_server(std::vector<std::string> args);
};

// The verified Message inside a frame read by test_client (aligned copy kept by the caller).
const protocol::Message* message_of(const std::vector<uint8_t>& frame);

// A path in /tmp unique to this test process, for a --stats-json or --record file; the file
// is removed when the process ends.
std::string temp_path(const std::string& name);
// A whole file; empty when missing.
std::string read_file(const std::string& path);

}  // namespace arena::test
