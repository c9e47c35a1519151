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

// Sends raw bytes from a fresh UDP socket (a new source port) to 127.0.0.1:port.
void send_raw_datagram(uint16_t port, std::span<const uint8_t> bytes);

}  // namespace arena::test
