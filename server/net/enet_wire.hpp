#pragma once
// What the server reads of ENet 1.3's datagrams before ENet does (enet/protocol.h), for the
// connect gate (udp_connect_gate.hpp) and the handshake's completion (udp_handshake.hpp). The
// constants are repeated here so that both build without ENet (the gate's fuzz target does).
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

namespace arena::net::enet_wire {

constexpr std::uint16_t max_peer_id = 0xFFF;  // a datagram to no peer yet: a connect
constexpr std::uint16_t flag_compressed = 1u << 14;
constexpr std::uint16_t flag_sent_time = 1u << 15;
constexpr std::uint16_t session_mask = 3u << 12;
constexpr int session_shift = 12;
constexpr std::uint8_t command_mask = 0x0F;
constexpr std::uint8_t command_acknowledge = 1;
constexpr std::uint8_t command_connect = 2;
constexpr std::uint8_t command_send_reliable = 6;
constexpr std::uint8_t command_send_unreliable = 7;
constexpr std::uint8_t command_send_fragment = 8;
constexpr std::uint8_t command_send_unsequenced = 9;
constexpr std::uint8_t command_send_unreliable_fragment = 12;
constexpr std::uint8_t control_channel = 0xFF;
constexpr std::size_t command_header = 4;        // command, channel, reliable sequence number
constexpr std::size_t connect_command = 48;      // sizeof(ENetProtocolConnect)
constexpr std::size_t connect_data_offset = 44;  // offsetof(ENetProtocolConnect, data)
constexpr std::size_t checksum_bytes = 4;        // after the header, on a host that uses one
// The fixed size of each command by its number (ENet's commandSizes: sizeof its struct, before
// the data of a send command); 0: no such command, ENet stops reading the datagram there.
constexpr std::array<std::uint8_t, 13> command_sizes = {0, 8, 48, 44, 8, 4, 6, 8, 24, 8, 12, 16, 24};

}  // namespace arena::net::enet_wire

namespace arena::net {

// The fixed header of an ENet 1.3 datagram.
struct datagram_header {
    std::uint16_t peer_id = 0;  // enet_wire::max_peer_id: to no peer yet (a connect)
    std::uint8_t session = 0;   // the 2 session bits
    bool compressed = false;
    std::size_t size = 0;  // bytes before the first command (or the checksum): 2, or 4 with the sent time
};

// Nothing when shorter than its header.
[[nodiscard]] inline std::optional<datagram_header> read_datagram_header(std::span<const std::uint8_t> datagram) {
    using namespace enet_wire;
    if (datagram.size() < 2) return std::nullopt;
    const auto field = static_cast<std::uint16_t>((datagram[0] << 8) | datagram[1]);  // network order
    datagram_header header;
    header.size = (field & flag_sent_time) ? 4 : 2;
    if (datagram.size() < header.size) return std::nullopt;
    header.compressed = (field & flag_compressed) != 0;
    header.session = static_cast<std::uint8_t>((field & session_mask) >> session_shift);
    header.peer_id = static_cast<std::uint16_t>(field & ~(flag_sent_time | flag_compressed | session_mask));
    return header;
}

}  // namespace arena::net
