#pragma once
// Test helpers: ENet 1.3 datagrams written by hand (enet/protocol.h), for conversations no ENet
// client would hold: a handshake left half-open, fragment commands no sender would write.
#include <cstdint>
#include <optional>
#include <vector>

#include "udp_client.hpp"

namespace arena::test {

// A CONNECT to no peer yet, with a sent time: CONNECT | ACKNOWLEDGE on the control channel,
// sequence 1, its fields in network order. 52 bytes.
std::vector<uint8_t> enet_connect_datagram(uint32_t connect_id);

// What the server's VERIFY_CONNECT told the client.
struct raw_enet_peer {
    uint16_t peer_id = 0;  // the server's slot for us: every later datagram names it
    uint8_t session = 0;   // the session bits a client sends with
};

// CONNECT, the server's VERIFY_CONNECT, and its acknowledgement: the server counts the peer
// connected. Nothing when no VERIFY_CONNECT comes within 2 s.
std::optional<raw_enet_peer> raw_enet_handshake(raw_udp_socket& socket, uint32_t connect_id);

// A datagram to `peer` holding `count` SEND_FRAGMENT commands on channel 0, each the first
// fragment (number 0) of its own message, starting at reliable sequence `first_sequence`, and
// each carrying one byte: `fragment_count` fragments of `total_length` bytes claimed.
std::vector<uint8_t> enet_fragment_starts(raw_enet_peer peer, uint16_t first_sequence, int count,
                                          uint32_t fragment_count, uint32_t total_length);

// A datagram to `peer` with `frame` as reliable sequence `sequence` on channel 0.
std::vector<uint8_t> enet_reliable_datagram(raw_enet_peer peer, uint16_t sequence, const std::vector<uint8_t>& frame);

}  // namespace arena::test
