#pragma once
// Test helper: a blocking ENet client of arena-server's UDP transport (one host, one peer),
// and a raw UDP socket for datagrams ENet would never send.
#include <enet/enet.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "protocol/arena_generated.h"
#include "protocol/messages.hpp"

namespace arena::test {

class udp_client {
public:
    // Connects to 127.0.0.1:port with `connect_data`; connected() says whether ENet's
    // handshake completed within `timeout`.
    explicit udp_client(uint16_t port, std::chrono::milliseconds timeout = std::chrono::milliseconds(2000),
                        enet_uint32 connect_data = 0);
    ~udp_client();
    udp_client(const udp_client&) = delete;
    udp_client& operator=(const udp_client&) = delete;

    bool connected() const { return connected_; }
    bool disconnected() const { return disconnected_; }
    // Control frames go reliable on channel 0, inputs unsequenced on channel 1.
    void send_reliable(std::span<const uint8_t> frame);
    void send_unreliable(std::span<const uint8_t> frame);
    // The next frame, or nothing on timeout or disconnect.
    std::optional<std::vector<uint8_t>> read_frame(std::chrono::milliseconds timeout);
    std::optional<std::vector<uint8_t>> read_until(protocol::Payload type, std::chrono::milliseconds timeout);
    // Services ENet for `duration`, keeping what arrives for read_frame.
    void pump(std::chrono::milliseconds duration);

private:
    bool service_once(int timeout_ms);
    ENetHost* host_ = nullptr;
    ENetPeer* peer_ = nullptr;
    bool connected_ = false;
    bool disconnected_ = false;
    std::vector<std::vector<uint8_t>> received_;
};

// A UDP socket of its own (one source port) to 127.0.0.1:port, for an ENet conversation
// written by hand: a handshake with a step left out, say.
class raw_udp_socket {
public:
    // `source`: the loopback address to send from (any of 127.0.0.0/8 on Linux), for a test
    // that needs several source hosts.
    explicit raw_udp_socket(uint16_t port, const char* source = "127.0.0.1");
    ~raw_udp_socket();
    raw_udp_socket(const raw_udp_socket&) = delete;
    raw_udp_socket& operator=(const raw_udp_socket&) = delete;

    void send(std::span<const uint8_t> bytes);
    // The next datagram from the server, or nothing on timeout.
    std::optional<std::vector<uint8_t>> receive(std::chrono::milliseconds timeout);

private:
    int fd_ = -1;
};

// Sends raw bytes from a fresh UDP socket (a new source port) to 127.0.0.1:port.
void send_raw_datagram(uint16_t port, std::span<const uint8_t> bytes);

}  // namespace arena::test
