#include "server/net/udp_peer_commands.hpp"

#include <array>
#include <cstddef>

#include "server/net/enet_wire.hpp"

namespace arena::net {

namespace {

using namespace enet_wire;

std::uint16_t u16_at(std::span<const std::uint8_t> d, std::size_t at) {  // network order
    return static_cast<std::uint16_t>(d[at] << 8 | d[at + 1]);
}

std::uint32_t u32_at(std::span<const std::uint8_t> d, std::size_t at) {
    return static_cast<std::uint32_t>(u16_at(d, at)) << 16 | u16_at(d, at + 2);
}

// A fragment's claim is one ENet could have sent: a message no larger than a client frame, in
// no more fragments than its length needs at this fragment's length (every fragment but the
// last is as long as the first, and the last is shorter: ceil(total / length) >= the count
// for each of them).
bool fragment_claim_fits(std::uint32_t count, std::uint32_t total, std::uint32_t length,
                         const peer_command_limits& limits) {
    if (length == 0 || total > limits.max_message) return false;
    const std::uint64_t needed = (static_cast<std::uint64_t>(total) + length - 1) / length;
    return count <= needed;
}

}  // namespace

peer_commands_verdict judge_peer_commands(std::span<const std::uint8_t> datagram, bool said_hello,
                                          const peer_command_limits& limits) {
    const auto header = read_datagram_header(datagram);
    if (!header || header->compressed) return peer_commands_verdict::pass;
    std::size_t at = header->size;
    while (at + command_header <= datagram.size()) {
        const std::uint8_t number = datagram[at] & command_mask;
        if (number >= command_sizes.size() || command_sizes[number] == 0) break;  // ENet stops here
        const std::size_t size = command_sizes[number];
        if (at + size > datagram.size()) break;
        std::size_t data = 0;
        switch (number) {
            case command_send_reliable:
                if (!said_hello && u16_at(datagram, at + 2) > limits.max_reliable_before_hello)
                    return peer_commands_verdict::before_hello;
                data = u16_at(datagram, at + 4);
                break;
            case command_send_unreliable:
                if (!said_hello) return peer_commands_verdict::before_hello;
                data = u16_at(datagram, at + 6);
                break;
            case command_send_unsequenced:  // delivered at once, never held
                data = u16_at(datagram, at + 6);
                break;
            case command_send_fragment:
            case command_send_unreliable_fragment:
                if (!said_hello) return peer_commands_verdict::before_hello;
                data = u16_at(datagram, at + 6);
                if (!fragment_claim_fits(u32_at(datagram, at + 8), u32_at(datagram, at + 16),
                                         static_cast<std::uint32_t>(data), limits))
                    return peer_commands_verdict::fragment_oversize;
                break;
            default:
                break;
        }
        at += size + data;  // past the end: ENet stops there too
    }
    return peer_commands_verdict::pass;
}

}  // namespace arena::net
