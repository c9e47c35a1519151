#pragma once
// Test helper: a WebSocket client of arena-server's /ws (Beast's, on its own io_context, every
// call bounded by a timeout), and a raw HTTP request over a plain socket.
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "protocol/arena_generated.h"
#include "protocol/messages.hpp"

namespace arena::test {

class ws_client {
public:
    // Connects to 127.0.0.1:port and upgrades `target`, with an Origin header unless empty;
    // receive_buffer > 0 shrinks the socket's receive buffer (a client that fills up fast);
    // `from`: the local address to connect from (another 127/8 address: another host), or "".
    explicit ws_client(uint16_t port, const std::string& origin = "", const std::string& target = "/ws",
                       int receive_buffer = 0, const std::string& from = "");
    ~ws_client();
    ws_client(const ws_client&) = delete;
    ws_client& operator=(const ws_client&) = delete;

    // True once the upgrade succeeded; otherwise refused_status() is the HTTP answer's status
    // (0 when there was none).
    bool open() const;
    int refused_status() const;

    // One binary message (a frame); a text message; a message in fragments of `piece` bytes.
    bool send_binary(const std::vector<uint8_t>& bytes);
    bool send_text(const std::string& text);
    bool send_fragmented(const std::vector<uint8_t>& bytes, size_t piece);
    bool ping();

    // The next binary message, or nothing on timeout or a closed connection.
    std::optional<std::vector<uint8_t>> read_message(
        std::chrono::milliseconds timeout = std::chrono::milliseconds(3000));
    // Messages until one of `type` (others are dropped).
    std::optional<std::vector<uint8_t>> read_until(protocol::Payload type,
                                                   std::chrono::milliseconds timeout = std::chrono::milliseconds(3000));
    // True when the server ended the connection within `timeout` (messages before are skipped).
    bool closed_by_peer(std::chrono::milliseconds timeout = std::chrono::milliseconds(3000));
    // The close code the server sent (0: none seen yet).
    int close_code() const;

private:
    struct impl;
    std::unique_ptr<impl> impl_;
};

// Sends `request` as is on a new connection to 127.0.0.1:port (from the local address `from`
// unless empty) and returns everything the server answered before it closed (or `timeout`
// passed).
std::string raw_http(uint16_t port, const std::string& request,
                     std::chrono::milliseconds timeout = std::chrono::milliseconds(3000), const std::string& from = "");

}  // namespace arena::test
