#include "udp_raw_enet.hpp"

#include <chrono>

namespace arena::test {

namespace {

void put_u16(std::vector<uint8_t>& d, uint32_t v) {
    d.push_back(static_cast<uint8_t>(v >> 8));
    d.push_back(static_cast<uint8_t>(v));
}

void put_u32(std::vector<uint8_t>& d, uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) d.push_back(static_cast<uint8_t>(v >> shift));
}

// The header of a datagram to a peer, with a sent time: without one ENet acknowledges nothing
// and stops reading the datagram after its first command that asks for an acknowledgement.
std::vector<uint8_t> peer_header(raw_enet_peer peer) {
    std::vector<uint8_t> d;
    put_u16(d, 0x8000u | static_cast<uint32_t>(peer.session) << 12 | peer.peer_id);
    put_u16(d, 0);  // sent time (ms), echoed in the acknowledgements
    return d;
}

}  // namespace

std::vector<uint8_t> enet_connect_datagram(uint32_t connect_id) {
    // Then our peer id 0, and 0xFF for both sessions: the server picks them.
    std::vector<uint8_t> d = {0x8F, 0xFF, 0x00, 0x00, 0x82, 0xFF, 0x00, 0x01, 0x00, 0x00, 0xFF, 0xFF};
    for (uint32_t field : {1400u, 32768u, 2u, 0u, 0u, 5000u, 2u, 2u, connect_id, 0u}) put_u32(d, field);
    // mtu, window, channels, bandwidth in and out, throttle interval, acceleration, deceleration
    return d;
}

std::optional<raw_enet_peer> raw_enet_handshake(raw_udp_socket& socket, uint32_t connect_id) {
    socket.send(enet_connect_datagram(connect_id));
    for (;;) {
        auto datagram = socket.receive(std::chrono::milliseconds(2000));
        if (!datagram) return std::nullopt;
        const std::vector<uint8_t>& v = *datagram;
        const bool sent_time = (v[0] & 0x80) != 0;
        const size_t at = sent_time ? 4 : 2;
        if (v.size() < at + 44 || (v[at] & 0x0F) != 3) continue;  // not VERIFY_CONNECT
        raw_enet_peer peer;
        peer.peer_id = static_cast<uint16_t>((v[at + 4] << 8) | v[at + 5]);
        peer.session = v[at + 7];  // its outgoingSessionID: the session a client sends with
        // ACKNOWLEDGE of the VERIFY_CONNECT's sequence, echoing its sent time.
        std::vector<uint8_t> ack = peer_header(peer);
        ack.insert(ack.end(), {0x01, 0xFF, v[at + 2], v[at + 3], v[at + 2], v[at + 3]});
        ack.insert(ack.end(), {sent_time ? v[2] : uint8_t{0}, sent_time ? v[3] : uint8_t{0}});
        socket.send(ack);
        return peer;
    }
}

std::vector<uint8_t> enet_fragment_starts(raw_enet_peer peer, uint16_t first_sequence, int count,
                                          uint32_t fragment_count, uint32_t total_length) {
    std::vector<uint8_t> d = peer_header(peer);
    for (int i = 0; i < count; ++i) {
        const auto sequence = static_cast<uint16_t>(first_sequence + i);
        d.insert(d.end(), {0x88, 0x00});  // SEND_FRAGMENT | ACKNOWLEDGE, channel 0
        put_u16(d, sequence);             // this fragment's reliable sequence number
        put_u16(d, sequence);             // the message's start sequence number: its first fragment
        put_u16(d, 1);                    // one byte of data
        put_u32(d, fragment_count);
        put_u32(d, 0);  // fragment number
        put_u32(d, total_length);
        put_u32(d, 0);  // offset
        d.push_back(0x41);
    }
    return d;
}

std::vector<uint8_t> enet_reliable_datagram(raw_enet_peer peer, uint16_t sequence, const std::vector<uint8_t>& frame) {
    std::vector<uint8_t> d = peer_header(peer);
    d.insert(d.end(), {0x86, 0x00});  // SEND_RELIABLE | ACKNOWLEDGE, channel 0
    put_u16(d, sequence);
    put_u16(d, static_cast<uint32_t>(frame.size()));
    d.insert(d.end(), frame.begin(), frame.end());
    return d;
}

}  // namespace arena::test
