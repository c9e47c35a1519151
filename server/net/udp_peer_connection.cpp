#include "server/net/udp_peer_connection.hpp"

#include <arpa/inet.h>

#include "server/host/intake.hpp"
#include "server/net/udp_transport.hpp"

namespace arena::net {

namespace {

std::string describe(const ENetAddress& address) {
    char text[INET_ADDRSTRLEN] = {};
    in_addr in{};
    in.s_addr = address.host;  // ENet keeps the IPv4 address in network order
    ::inet_ntop(AF_INET, &in, text, sizeof text);
    return std::string(text) + ":" + std::to_string(address.port);
}

}  // namespace

udp_peer_connection::udp_peer_connection(udp_transport& owner, ENetPeer* peer, uint64_t id)
    : owner_(owner), peer_(peer), id_(id), peer_text_(describe(peer->address)) {}

bool udp_peer_connection::receive(std::span<const uint8_t> datagram, int64_t arrival_ns) {
    if (closing_) return false;
    host::intake& intake = owner_.intake();
    // One datagram, one frame: the same framing as TCP, so a frame that is too large is
    // refused by its prefix, and the frame lands 8-byte aligned for the verifier.
    const size_t used = reader_.feed(datagram);
    if (reader_.failed()) {
        intake.refuse_unreadable(*this, reader_);
        return false;
    }
    if (!reader_.has_frame() || used != datagram.size()) {
        intake.refuse(*this, {protocol::RejectCode::bad_request,
                              "a datagram of " + std::to_string(datagram.size()) + " bytes is not exactly one frame"});
        return false;
    }
    const host::intake_result taken = intake.take(*this, reader_.frame(), arrival_ns);
    if (const protocol::Message* message = taken.message) {
        // What the gate and the snapshot copies need to know of the peer: whether it said
        // Hello (from then on it may send fragments), and which snapshot it acknowledged.
        if (message->payload_type() == protocol::Payload::Hello) said_hello_ = true;
        if (const protocol::Input* input = message->payload_as_Input()) {
            loss_.input_arrived(input->sequence());
            loss_.acked(input->snapshot_ack());
        }
    }
    const bool go_on = taken.go_on;
    reader_.next();
    if (!go_on) close_after({});  // a Bye from the client; after a refusal this changes nothing
    return go_on;
}

void udp_peer_connection::send_packet(std::span<const uint8_t> bytes, enet_uint8 channel, enet_uint32 flags) {
    if (peer_ == nullptr || bytes.empty()) return;
    ENetPacket* packet = enet_packet_create(bytes.data(), bytes.size(), flags);
    if (packet == nullptr) return;
    if (enet_peer_send(peer_, channel, packet) != 0) {
        enet_packet_destroy(packet);  // not queued (the peer is not connected): still ours
        return;
    }
    owner_.count_out(bytes.size());
    owner_.flush_soon();
}

size_t udp_peer_connection::snapshot_budget() const {
    return owner_.snapshot_budget();
}

void udp_peer_connection::send(protocol::frame_bytes frame) {
    if (closing_) return;
    send_packet(frame, channel_reliable, ENET_PACKET_FLAG_RELIABLE);
}

void udp_peer_connection::send_snapshot(const protocol::snapshot_encoder& snapshot, uint32_t ack_sequence) {
    if (closing_) return;
    snapshot.copy_with_ack(ack_sequence, snapshot_);
    send_snapshot_bytes(snapshot_);
}

void udp_peer_connection::send_snapshot_frame(std::span<const uint8_t> frame) {
    if (closing_) return;
    send_snapshot_bytes(frame);
}

void udp_peer_connection::send_snapshot_bytes(std::span<const uint8_t> bytes) {
    // One datagram, unsequenced: a lost snapshot is replaced by the next one, never resent,
    // and a late one is dropped by the client. A snapshot over the datagram budget (a full
    // view of a crowded area) goes as unreliable fragments: it arrives whole or not at all,
    // and the client keeps acking its older baseline until one does. Delta snapshots are
    // built within the budget (snapshot_budget() above); what still goes over (BodyState
    // snapshots of a crowded view) is counted.
    // Our own frame (size-prefixed, aligned), verified when it was built: its tick is read as is.
    if (bytes.size() >= protocol::frame_prefix_size + protocol::min_frame_body) {
        if (const auto* snapshot = protocol::GetSizePrefixedMessage(bytes.data())->payload_as_Snapshot())
            loss_.sent(snapshot->tick());
    }
    if (bytes.size() <= owner_.snapshot_budget()) {
        send_packet(bytes, channel_datagrams, ENET_PACKET_FLAG_UNSEQUENCED);
        // Its copies a tick apart (never at once: a burst of loss would take them together).
        // A newer snapshot replaces the copies of an older one; the client drops duplicates.
        const uint32_t copies = copies_now();
        copies_left_ = copies > 1 ? copies - 1 : 0;
        if (copies_left_ > 0) {
            copy_.assign(bytes.begin(), bytes.end());
            copy_due_ns_ = owner_.now_ns() + owner_.tick_ns();
        }
    } else {
        owner_.count_fragmented_snapshot();
        send_packet(bytes, channel_datagrams, ENET_PACKET_FLAG_UNRELIABLE_FRAGMENT);
    }
}

uint32_t udp_peer_connection::copies_now() const {
    const uint32_t configured = owner_.snapshot_copies();
    return configured == 0 ? loss_.copies() : configured;  // 0: auto
}

void udp_peer_connection::send_due_copy(int64_t now_ns) {
    if (copies_left_ == 0 || closing_ || now_ns < copy_due_ns_) return;
    --copies_left_;
    copy_due_ns_ = now_ns + owner_.tick_ns();
    owner_.count_snapshot_copy();
    send_packet(copy_, channel_datagrams, ENET_PACKET_FLAG_UNSEQUENCED);
}

void udp_peer_connection::close(protocol::RejectCode code, std::string_view reason) {
    close_after(protocol::encode_reject(code, reason));
}

void udp_peer_connection::close_with_bye(std::string_view reason) {
    close_after(protocol::encode_bye(reason));
}

void udp_peer_connection::close_with_result(std::string_view reason, const protocol::match_result& result) {
    close_after(protocol::encode_bye(reason, &result));
}

void udp_peer_connection::close_after(const protocol::frame_bytes& last_frame) {
    if (closing_) return;
    send_packet(last_frame, channel_reliable, ENET_PACKET_FLAG_RELIABLE);
    closing_ = true;
    closing_since_ns_ = owner_.now_ns();
    // ENet disconnects once everything queued is acknowledged; the transport resets the peer
    // if that takes longer than the close grace.
    if (peer_ != nullptr) enet_peer_disconnect_later(peer_, 0);
    owner_.flush_now();  // at shutdown the io_context may stop before a posted flush
}

}  // namespace arena::net
