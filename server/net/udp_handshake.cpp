#include "server/net/udp_handshake.hpp"

namespace arena::net {

namespace {

// ENet 1.3's wire constants (enet/protocol.h), repeated so that this file builds without ENet.
constexpr std::uint16_t flag_compressed = 1u << 14;
constexpr std::uint16_t flag_sent_time = 1u << 15;
constexpr std::uint16_t session_mask = 3u << 12;
constexpr int session_shift = 12;
constexpr std::uint8_t command_mask = 0x0F;
constexpr std::uint8_t command_acknowledge = 1;
constexpr std::uint8_t control_channel = 0xFF;
constexpr std::size_t command_header = 4;  // command, channel, reliable sequence number

void put_u16(std::vector<std::uint8_t>& out, std::uint16_t value) {  // network order
    out.push_back(static_cast<std::uint8_t>(value >> 8));
    out.push_back(static_cast<std::uint8_t>(value & 0xFF));
}

}  // namespace

std::optional<datagram_header> read_datagram_header(std::span<const std::uint8_t> datagram) {
    if (datagram.size() < 2) return std::nullopt;
    const auto field = static_cast<std::uint16_t>((datagram[0] << 8) | datagram[1]);
    datagram_header header;
    header.size = (field & flag_sent_time) ? 4 : 2;
    if (datagram.size() < header.size) return std::nullopt;
    header.compressed = (field & flag_compressed) != 0;
    header.session = static_cast<std::uint8_t>((field & session_mask) >> session_shift);
    header.peer_id = static_cast<std::uint16_t>(field & ~(flag_sent_time | flag_compressed | session_mask));
    return header;
}

bool acknowledge_verify_connect(std::span<const std::uint8_t> datagram, unacknowledged_verify verify,
                                std::vector<std::uint8_t>& out) {
    const auto header = read_datagram_header(datagram);
    if (!header || header->compressed || datagram.size() < header->size + command_header) return false;
    if ((datagram[header->size] & command_mask) == command_acknowledge) return false;
    out.assign(datagram.begin(), datagram.begin() + static_cast<std::ptrdiff_t>(header->size));
    // ENetProtocolAcknowledge, as ENet writes its own: the command header carries the sequence
    // number it acknowledges, then that number again and the 16 low bits of its sent time.
    out.push_back(command_acknowledge);
    out.push_back(control_channel);
    put_u16(out, verify.sequence);
    put_u16(out, verify.sequence);
    put_u16(out, static_cast<std::uint16_t>(verify.sent_ms & 0xFFFF));
    out.insert(out.end(), datagram.begin() + static_cast<std::ptrdiff_t>(header->size), datagram.end());
    return true;
}

}  // namespace arena::net
