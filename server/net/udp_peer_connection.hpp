#pragma once
// One UDP client: an ENet peer as the match sees it. Control messages (Welcome, Pong, Reject,
// Bye) go on the reliable, ordered channel; snapshots on the unreliable one, each in one
// datagram. Every datagram from the peer must be exactly one size-prefixed frame; it is
// verified with the same limits as TCP before the match reads a field.
#include <enet/enet.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "protocol/framing.hpp"
#include "server/match/connection.hpp"
#include "server/net/snapshot_loss.hpp"

namespace arena::net {

class udp_transport;

// ENet channels: 0 is reliable and ordered, 1 carries unreliable datagrams.
inline constexpr enet_uint8 channel_reliable = 0;
inline constexpr enet_uint8 channel_datagrams = 1;
inline constexpr size_t udp_channel_count = 2;

class udp_peer_connection : public match::connection {
public:
    udp_peer_connection(udp_transport& owner, ENetPeer* peer, uint64_t id);

    void send(protocol::frame_bytes frame) override;
    void send_snapshot(const protocol::snapshot_encoder& snapshot, uint32_t ack_sequence) override;
    void send_snapshot_frame(std::span<const uint8_t> frame) override;
    void close(protocol::RejectCode code, std::string_view reason) override;
    void close_with_bye(std::string_view reason) override;
    void close_with_result(std::string_view reason, const protocol::match_result& result) override;
    std::string_view peer() const override { return peer_text_; }
    size_t snapshot_budget() const override;

    // One datagram from the peer: framed, verified, handed to the match. False: the
    // connection is over (the match refused it or the client said Bye).
    bool receive(std::span<const uint8_t> datagram, int64_t arrival_ns);

    // Closing: the last word is queued and ENet disconnects once it is delivered; the match
    // has forgotten this connection.
    bool closing() const { return closing_; }
    int64_t closing_since_ns() const { return closing_since_ns_; }
    uint64_t id() const { return id_; }
    // Its Hello reached the match: from now on it may send what ENet holds for later (fragments).
    bool said_hello() const { return said_hello_; }
    ENetPeer* enet_peer() const { return peer_; }
    // Sends the pending copy of the last snapshot when its time came (udp_options::snapshot_copies).
    void send_due_copy(int64_t now_ns);
    // Its snapshot loss, measured from its acks (used with --udp-snapshot-copies auto).
    const snapshot_loss& loss() const { return loss_; }
    // ENet reset the peer (it is gone): nothing may be sent any more.
    void forget_peer() { peer_ = nullptr; }

private:
    void send_packet(std::span<const uint8_t> bytes, enet_uint8 channel, enet_uint32 flags);
    void send_snapshot_bytes(std::span<const uint8_t> bytes);
    void close_after(const protocol::frame_bytes& last_frame);
    uint32_t copies_now() const;  // times the next snapshot goes

    udp_transport& owner_;
    ENetPeer* peer_;
    uint64_t id_;
    std::string peer_text_;
    protocol::frame_reader reader_;  // aligned storage for one datagram's frame
    std::vector<uint8_t> snapshot_;  // send_snapshot's copy with the ack patched in
    std::vector<uint8_t> copy_;      // the last snapshot datagram, to send again
    uint32_t copies_left_ = 0;       // times it is still to go
    int64_t copy_due_ns_ = 0;        // not before
    bool closing_ = false;
    bool said_hello_ = false;
    snapshot_loss loss_;
    int64_t closing_since_ns_ = 0;
};

}  // namespace arena::net
