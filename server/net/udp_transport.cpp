#include "server/net/udp_transport.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include "protocol/version.hpp"
#include "server/auth/join_token.hpp"
#include "server/host/log.hpp"
#include "server/net/udp_handshake.hpp"
#include "server/net/udp_peer_commands.hpp"

namespace arena::net {

namespace {

// The transport whose host is being serviced: ENet's intercept callback has no user pointer.
// One thread services one host at a time.
thread_local udp_transport* servicing = nullptr;
thread_local int64_t servicing_now_ns = 0;

std::string address_text(const ENetAddress& address) {
    char text[64] = {};
    if (enet_address_get_host_ip(&address, text, sizeof text) != 0) return "?";
    return text;
}

// Datagrams taken from the socket per wake-up before the tick gets the thread back.
constexpr int max_events_per_service = 4096;

}  // namespace

udp_transport::udp_transport(host::transport_host& host, udp_options options)
    : io_(host.io()), owner_(host), options_(options), readable_(host.io()), timer_(host.io()), gate_(options.gate) {
    if (enet_initialize() != 0) throw std::runtime_error("udp: cannot initialise ENet");
    if (const auto& secret = host.options().token_secret) {
        gate_.require_connect_key([secret = *secret](int64_t unix_seconds) { return secret.connect_key(unix_seconds); },
                                  auth::connect_key_window_s);
    }
}

udp_transport::~udp_transport() {
    stopped_ = true;
    boost::system::error_code ec;
    readable_.close(ec);  // our duplicate of ENet's descriptor
    timer_.cancel();
    connections_.clear();
    if (host_ != nullptr) {
        enet_host_flush(host_);
        enet_host_destroy(host_);
    }
    enet_deinitialize();
}

match::match& udp_transport::match_of(const match::connection& c) {
    return owner_.matches().match_of(c);
}

host::intake& udp_transport::intake() {
    return owner_.intake();
}

int64_t udp_transport::now_ns() const {
    return owner_.now_ns();
}

void udp_transport::count_out(size_t bytes) {
    owner_.count_out(bytes);
}

int64_t udp_transport::tick_ns() const {
    return owner_.tick_ns();
}

void udp_transport::send_due_copies() {
    if (options_.snapshot_copies == 1) return;
    const int64_t now = now_ns();
    for (auto& [id, c] : connections_) c->send_due_copy(now);
}

void udp_transport::start() {
    ENetAddress address{};
    const std::string& bind = owner_.options().bind;
    if (enet_address_set_host_ip(&address, bind.c_str()) != 0)
        throw std::runtime_error("--udp-port: ENet binds IPv4 only; cannot bind '" + bind + "'");
    address.port = options_.port;
    // A peer slot per connection the matches may hold: --max-connections when given (a bound
    // for the whole transport), else a match's default limit for every match the process may
    // host; ENet's protocol numbers at most 4095 peers.
    const host::host_options& host_options = owner_.options();
    const uint64_t per_match = owner_.matches().default_match().rules().connection_limit();
    const uint64_t limit = options_.max_peers != 0                             ? options_.max_peers
                           : host_options.match.admission.max_connections != 0 ? per_match
                                                                               : per_match * host_options.max_matches;
    const size_t peers = std::clamp<size_t>(limit, 1, ENET_PROTOCOL_MAXIMUM_PEER_ID);
    host_ = enet_host_create(&address, peers, udp_channel_count, 0, 0);
    if (host_ == nullptr)
        throw std::runtime_error("--udp-port: cannot bind UDP " + bind + ":" + std::to_string(options_.port));
    host_->duplicatePeers = std::max<size_t>(1, options_.peers_per_address);
    // ENet checks a message's size against maximumPacketSize both ways, so it stays at the
    // largest frame we send (a Welcome carries the whole config); what a client may send, at
    // most a client frame, is checked by the gate (udp_peer_commands.hpp) before ENet reads it.
    host_->maximumPacketSize = protocol::frame_prefix_size + protocol::max_server_frame_body;
    host_->maximumWaitingData = options_.max_waiting_bytes;
    half_open_.assign(host_->peerCount, {});
    host_->intercept = &udp_transport::intercept;
    port_ = host_->address.port;
    const int fd = ::dup(host_->socket);
    if (fd < 0) throw std::runtime_error("--udp-port: cannot watch the UDP socket");
    readable_.assign(fd);
    std::printf("udp listening on %s:%u\n", bind.c_str(), port_);
    std::fflush(stdout);
    if (options_.snapshot_copies == 0)
        host::log_line(
            "udp: ENet on %s:%u, %zu peer slots, snapshots up to %zu bytes per datagram, each sent 1 or 2 "
            "times by each client's loss",
            bind.c_str(), port_, peers, options_.snapshot_budget);
    else
        host::log_line("udp: ENet on %s:%u, %zu peer slots, snapshots up to %zu bytes per datagram, each sent %u times",
                       bind.c_str(), port_, peers, options_.snapshot_budget, options_.snapshot_copies);
    wait_readable();
    arm_timer();
}

void udp_transport::wait_readable() {
    readable_.async_wait(boost::asio::posix::stream_descriptor::wait_read, [this](const boost::system::error_code& ec) {
        if (ec || stopped_) return;
        send_due_copies();
        service();
        wait_readable();
    });
}

void udp_transport::arm_timer() {
    timer_.expires_after(std::chrono::nanoseconds(options_.service_interval_ns));
    timer_.async_wait([this](const boost::system::error_code& ec) {
        if (ec || stopped_) return;
        service();
        reap_closing();
        reap_half_open();
        arm_timer();
    });
}

void udp_transport::flush_soon() {
    if (flush_posted_) return;
    flush_posted_ = true;
    boost::asio::post(io_, [this] {
        flush_posted_ = false;
        if (stopped_ || host_ == nullptr) return;
        send_due_copies();
        enet_host_flush(host_);
    });
}

void udp_transport::flush_now() {
    if (!stopped_ && host_ != nullptr) enet_host_flush(host_);
}

void udp_transport::service() {
    if (gate_.requires_connect_key()) gate_.set_wall_clock(auth::unix_now());  // derives keys once per window
    ENetEvent event{};
    for (int i = 0; i < max_events_per_service; ++i) {
        servicing = this;
        servicing_now_ns = now_ns();
        const int got = enet_host_service(host_, &event, 0);
        servicing = nullptr;
        if (got <= 0) break;  // nothing more now (or a socket error, which ENet recovers from)
        switch (event.type) {
            case ENET_EVENT_TYPE_CONNECT:
                on_connect(event.peer);
                break;
            case ENET_EVENT_TYPE_RECEIVE:
                on_receive(event.peer, event.packet);
                break;
            case ENET_EVENT_TYPE_DISCONNECT:
                on_disconnect(event.peer);
                break;
            case ENET_EVENT_TYPE_NONE:
                break;
        }
    }
}

int ENET_CALLBACK udp_transport::intercept(ENetHost* host, ENetEvent*) {
    if (servicing == nullptr) return 0;
    return servicing->admit(host) ? 0 : 1;  // 1: ENet drops the datagram
}

bool udp_transport::admit(ENetHost* host) {
    const std::span<const uint8_t> datagram(host->receivedData, host->receivedDataLength);
    const std::string address = address_text(host->receivedAddress);
    switch (gate_.judge(datagram, address, servicing_now_ns)) {
        case gate_verdict::pass:
            if (auto why = peer_commands_refusal(host)) return refuse(*why, address);
            acknowledge_proven_handshake(host);
            return true;
        case gate_verdict::refuse_shape:
            return refuse(udp_refusal::shape, address);
        case gate_verdict::refuse_rate:
            return refuse(udp_refusal::rate, address);
        case gate_verdict::refuse_key:
            return refuse(udp_refusal::connect_key, address);
        case gate_verdict::refuse_before_hello:  // judge_peer's verdicts, never judge's
        case gate_verdict::refuse_fragment:
        case gate_verdict::connect:
            break;
    }
    // ENet drops a connect it has no slot for without a word: say so here.
    if (auto why = make_room_for_connect(host, host->receivedAddress)) return refuse(*why, address);
    return true;
}

std::optional<udp_refusal> udp_transport::peer_commands_refusal(ENetHost* host) {
    const std::span<const uint8_t> datagram(host->receivedData, host->receivedDataLength);
    // Said Hello: the slot's peer, on this address, has a connection whose Hello reached the
    // match. Any other datagram ENet drops (wrong address) or holds before Hello.
    bool said_hello = false;
    if (const auto header = read_datagram_header(datagram); header && header->peer_id < host->peerCount) {
        const ENetPeer& peer = host->peers[header->peer_id];
        const auto* c = static_cast<const udp_peer_connection*>(peer.data);
        said_hello = c != nullptr && c->said_hello() && peer.address.host == host->receivedAddress.host &&
                     peer.address.port == host->receivedAddress.port;
    }
    switch (gate_.judge_peer(datagram, said_hello)) {
        case gate_verdict::refuse_before_hello:
            return udp_refusal::before_hello;
        case gate_verdict::refuse_fragment:
            return udp_refusal::fragment;
        default:
            return std::nullopt;
    }
}

void udp_transport::acknowledge_proven_handshake(ENetHost* host) {
    // udp_handshake.hpp: from a peer whose acknowledgement of VERIFY_CONNECT ENet still waits
    // for, on its address and session, a datagram proves that VERIFY_CONNECT arrived.
    const std::span<const uint8_t> datagram(host->receivedData, host->receivedDataLength);
    const auto header = read_datagram_header(datagram);
    if (!header || header->peer_id >= host->peerCount) return;
    ENetPeer& peer = host->peers[header->peer_id];
    if (peer.state != ENET_PEER_STATE_ACKNOWLEDGING_CONNECT || peer.address.host != host->receivedAddress.host ||
        peer.address.port != host->receivedAddress.port || header->session != peer.incomingSessionID)
        return;
    for (ENetListIterator it = enet_list_begin(&peer.sentReliableCommands);
         it != enet_list_end(&peer.sentReliableCommands); it = enet_list_next(it)) {
        const auto* sent = reinterpret_cast<const ENetOutgoingCommand*>(it);
        if ((sent->command.header.command & ENET_PROTOCOL_COMMAND_MASK) != ENET_PROTOCOL_COMMAND_VERIFY_CONNECT)
            continue;
        if (acknowledge_verify_connect(datagram, {sent->reliableSequenceNumber, sent->sentTime}, proven_handshake_)) {
            // ENet reads the datagram from here; its next one from its own buffer again.
            host->receivedData = proven_handshake_.data();
            host->receivedDataLength = proven_handshake_.size();
        }
        return;
    }
}

bool udp_transport::refuse(udp_refusal why, const std::string& address) {
    ++owner_.counters().udp_refused[std::string(udp_refusal_key(why))];
    if (auto line = refusals_.refused(why, address, servicing_now_ns)) host::log_line("%s", line->c_str());
    return false;
}

std::optional<udp_refusal> udp_transport::make_room_for_connect(ENetHost* host, const ENetAddress& from) {
    // ENet's own rule for a connect (enet_protocol_handle_connect): a disconnected slot, and
    // fewer than duplicatePeers slots already held by the same host. Ours on top: when no slot
    // is free, a half-open handshake gives its slot up, as a waiting TCP connection does
    // (admission.cpp): players behind one address may connect all at once while there is
    // room, and handshakes left half-open from any number of spoofed addresses cannot keep an
    // honest connect out, since they are always the ones holding the most.

    // Per address: its half-open handshakes, and the oldest of them (one not yet seen by the
    // reaper counts as new).
    struct half_open_held {
        uint32_t count = 0;
        ENetPeer* oldest = nullptr;
        int64_t oldest_since = 0;
    };
    bool free_slot = false;
    size_t same_host = 0;
    std::unordered_map<enet_uint32, half_open_held> half_open_by_host;
    for (size_t i = 0; i < host->peerCount; ++i) {
        ENetPeer& peer = host->peers[i];
        if (peer.state == ENET_PEER_STATE_DISCONNECTED) {
            free_slot = true;
            continue;
        }
        if (peer.state != ENET_PEER_STATE_CONNECTING && peer.address.host == from.host) ++same_host;
        if (peer.state != ENET_PEER_STATE_ACKNOWLEDGING_CONNECT) continue;
        half_open_held& held = half_open_by_host[peer.address.host];
        ++held.count;
        const int64_t since = i < half_open_.size() && half_open_[i].since_ns >= 0
                                  ? half_open_[i].since_ns
                                  : std::numeric_limits<int64_t>::max() - 1;
        if (held.oldest == nullptr || since < held.oldest_since) {
            held.oldest = &peer;
            held.oldest_since = since;
        }
    }
    if (same_host >= host->duplicatePeers) return udp_refusal::peer_limit;
    if (free_slot) return std::nullopt;
    if (half_open_by_host.empty()) return udp_refusal::peer_limit;  // every slot holds a connection
    const auto most = std::max_element(half_open_by_host.begin(), half_open_by_host.end(),
                                       [](const auto& a, const auto& b) { return a.second.count < b.second.count; });
    const auto own = half_open_by_host.find(from.host);
    if (own != half_open_by_host.end() && own->second.count >= most->second.count) return udp_refusal::half_open;
    enet_peer_reset(most->second.oldest);  // never connected: no connection of ours to forget
    return std::nullopt;
}

void udp_transport::reap_half_open() {
    // Checked every service interval (10 ms), long before ENet's first resend of
    // VERIFY_CONNECT (after its 500 ms initial round trip).
    const int64_t now = now_ns();
    for (size_t i = 0; i < host_->peerCount && i < half_open_.size(); ++i) {
        ENetPeer& peer = host_->peers[i];
        half_open_peer& seen = half_open_[i];
        if (peer.state != ENET_PEER_STATE_ACKNOWLEDGING_CONNECT) {
            seen.since_ns = -1;
            continue;
        }
        if (seen.since_ns < 0 || seen.connect_id != peer.connectID) seen = {peer.connectID, now};
        if (now - seen.since_ns >= options_.half_open_timeout_ns) {
            enet_peer_reset(&peer);  // never connected: no connection of ours to forget
            seen.since_ns = -1;
            continue;
        }
        // Sent once, never again: a connect that is not answered gets one VERIFY_CONNECT (48
        // bytes) for its 52. A client whose acknowledgement was lost proves the handshake
        // with its next datagram (udp_handshake.hpp); one that lost VERIFY_CONNECT resends its
        // CONNECT, answered afresh once this peer is reset.
        for (ENetList* list : {&peer.outgoingCommands, &peer.sentReliableCommands}) {
            for (ENetListIterator it = enet_list_begin(list); it != enet_list_end(list); it = enet_list_next(it)) {
                auto* command = reinterpret_cast<ENetOutgoingCommand*>(it);
                if ((command->command.header.command & ENET_PROTOCOL_COMMAND_MASK) !=
                    ENET_PROTOCOL_COMMAND_VERIFY_CONNECT)
                    continue;
                constexpr enet_uint32 never_ms = 3'600'000;  // longer than the peer lives
                command->roundTripTimeout = never_ms;
                command->roundTripTimeoutLimit = never_ms;
            }
        }
    }
}

void udp_transport::on_connect(ENetPeer* peer) {
    auto c = std::make_unique<udp_peer_connection>(*this, peer, next_id_++);
    peer->data = c.get();
    // A peer that stops answering is gone after 3 to 10 s (ENet's default is up to 30 s).
    enet_peer_timeout(peer, 0, 3000, 10000);
    udp_peer_connection& ref = *c;
    connections_.emplace(c->id(), std::move(c));
    owner_.connection_opened();
    match_of(ref).connect(ref);  // refused: it is closing, its Reject queued
}

void udp_transport::on_receive(ENetPeer* peer, ENetPacket* packet) {
    auto* c = static_cast<udp_peer_connection*>(peer->data);
    owner_.intake().count_bytes(packet->dataLength);
    if (c != nullptr && !c->closing()) c->receive(std::span<const uint8_t>(packet->data, packet->dataLength), now_ns());
    enet_packet_destroy(packet);
}

void udp_transport::on_disconnect(ENetPeer* peer) {
    auto* c = static_cast<udp_peer_connection*>(peer->data);
    peer->data = nullptr;
    if (c == nullptr) return;  // never connected
    c->forget_peer();
    if (!c->closing())
        match_of(*c).disconnect(*c, {match::close_cause::kind::connection_closed, {}, "the ENet peer disconnected"});
    if (auto it = connections_.find(c->id()); it != connections_.end()) forget(it);
}

std::map<uint64_t, std::unique_ptr<udp_peer_connection>>::iterator udp_transport::forget(
    std::map<uint64_t, std::unique_ptr<udp_peer_connection>>::iterator it) {
    auto next = connections_.erase(it);
    owner_.connection_closed();
    return next;
}

void udp_transport::count_fragmented_snapshot() {
    ++owner_.counters().snapshots_fragmented;
}

void udp_transport::count_snapshot_copy() {
    ++owner_.counters().snapshot_copies;
}

void udp_transport::reap_closing() {
    // A closing peer that does not acknowledge its last word within the close grace is reset.
    const int64_t now = now_ns();
    const int64_t grace = owner_.options().close_grace_ns;
    for (auto it = connections_.begin(); it != connections_.end();) {
        udp_peer_connection& c = *it->second;
        if (c.closing() && now - c.closing_since_ns() > grace) {
            if (ENetPeer* peer = c.enet_peer()) {
                peer->data = nullptr;
                enet_peer_reset(peer);
            }
            it = forget(it);
        } else {
            ++it;
        }
    }
}

}  // namespace arena::net
