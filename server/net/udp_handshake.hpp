#pragma once
// The last step of ENet's handshake, as the server needs it. A CONNECT takes a peer slot and is
// answered with VERIFY_CONNECT; ENet counts the peer connected only once that is acknowledged,
// and until then drops every other command of the peer without acknowledging it. The client
// is connected as soon as VERIFY_CONNECT arrives and sends at once (its Hello). When only its
// acknowledgement is lost, the Hello is dropped, and its resends fall due in step with the
// server's resends of VERIFY_CONNECT (both after 500 ms, then doubling): each resent Hello
// arrives a few ms before the acknowledgement its VERIFY_CONNECT brings, and is dropped again,
// so the Hello waits 1.5, 3.5 or 7.5 s.
//
// A datagram that carries the peer id and session the server chose is proof that
// VERIFY_CONNECT arrived: they come in it. So the transport puts the acknowledgement ENet waits
// for in front of such a datagram's commands, and ENet completes the handshake and reads the
// Hello in one go. It proves no more than the acknowledgement itself would (that has nothing
// secret either), so no limit of the connect gate changes.
//
// Plain C++ over bytes, tested without ENet; the transport checks the peer's state. The
// datagram's header is read by enet_wire.hpp's read_datagram_header (no checksum: the
// transport's host uses none).
#include <cstdint>
#include <span>
#include <vector>

#include "server/net/enet_wire.hpp"

namespace arena::net {

// The server's VERIFY_CONNECT that is not acknowledged yet: its reliable sequence number (on
// ENet's control channel 0xFF) and ENet's time (ms) it was last sent, which the acknowledgement
// echoes so that ENet's first round-trip sample stays true.
struct unacknowledged_verify {
    std::uint16_t sequence = 1;
    std::uint32_t sent_ms = 0;
};

// `datagram` with an ACKNOWLEDGE of `verify` put between its header and its first command,
// written to `out`. False, `out` untouched, when ENet needs no help or could not read the
// result: no command, compressed, or an acknowledgement first already (the peer's own).
[[nodiscard]] bool acknowledge_verify_connect(std::span<const std::uint8_t> datagram, unacknowledged_verify verify,
                                              std::vector<std::uint8_t>& out);

}  // namespace arena::net
