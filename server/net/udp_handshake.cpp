#include "server/net/udp_handshake.hpp"

namespace arena::net {

namespace {

void put_u16(std::vector<std::uint8_t>& out, std::uint16_t value) {  // network order
    out.push_back(static_cast<std::uint8_t>(value >> 8));
    out.push_back(static_cast<std::uint8_t>(value & 0xFF));
}

}  // namespace

bool acknowledge_verify_connect(std::span<const std::uint8_t> datagram, unacknowledged_verify verify,
                                std::vector<std::uint8_t>& out) {
    using namespace enet_wire;
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
