#pragma once
// What a datagram to a peer slot would make ENet keep, read before ENet reads it. ENet 1.3.17
// trusts a fragment's claimed count up to 2^20: a SEND_FRAGMENT start claiming 2^20 fragments
// of a 1-byte message made it allocate a 128 KiB bitmap (4000 of them: +528 MB of RSS, held
// until the peer timed out). And before the client's Hello, the only message an honest client
// sends is the Hello, which fits one datagram: anything ENet would hold for later (fragments,
// unreliable commands waiting for a reliable one, reliable commands far ahead of the next one
// expected) is there only to take memory.
//
// So the commands of each datagram are walked as ENet walks them (enet_protocol_handle_incoming_commands:
// each command's fixed size, then its data for the send commands; ENet stops at the first one
// that does not fit, and so does this), and the datagram is refused when one of them is:
//   - before Hello: a fragment, an unreliable command, or a reliable one with a sequence
//     number above peer_command_limits::max_reliable_before_hello;
//   - at any time: a fragment of a message larger than the largest client frame, or claiming
//     more fragments than its length needs at its own fragment length (ceil(total / length)).
// With these, what ENet holds for a peer before Hello is at most 2 channels x 4 reliable
// commands of one datagram each (ENet reads at most 4096 bytes): under 40 KiB; after Hello a
// fragment's bitmap is at most 1/8 of its message (8 KiB), and the messages ENet waits on are
// bounded by the host's maximumWaitingData.
//
// Plain C++ over bytes (no ENet): unit-tested and fuzzed with the connect gate.
#include <cstdint>
#include <span>

namespace arena::net {

enum class peer_commands_verdict : std::uint8_t {
    pass,               // ENet reads it
    before_hello,       // a fragment or a command ENet would queue, from a peer that said no Hello
    fragment_oversize,  // a fragment of a message too large, or claiming more fragments than it needs
};

struct peer_command_limits {
    std::uint32_t max_message = 4 + 64 * 1024;    // bytes: the largest client frame (prefix + protocol's body limit)
    std::uint16_t max_reliable_before_hello = 4;  // reliable sequence numbers a peer may use before Hello
};

// `said_hello`: the peer's Hello reached the match. A datagram ENet would drop whole (too short
// for its header, compressed: our host has no compressor) passes: ENet drops it.
[[nodiscard]] peer_commands_verdict judge_peer_commands(std::span<const std::uint8_t> datagram, bool said_hello,
                                                        const peer_command_limits& limits = {});

}  // namespace arena::net
