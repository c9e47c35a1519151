#pragma once
// The UDP transport: ENet peers feeding the same intake as TCP, on the host's io_context thread.
// It flushes what ENet queued in a handler posted by the first send (flush_soon), which also sends
// the snapshot copies that are due, so it needs no flush after the tick.
// ENet's socket is watched by Asio (a readable wait on a duplicate of its descriptor); each
// wake-up services ENet without blocking, and a short timer lets ENet resend and time out.
// Before ENet reads a datagram, the connect gate (udp_connect_gate.hpp) refuses connects over
// an address's rate and connect datagrams too small to be answered without amplification, and,
// when the server has a token secret, connects without its current connect key. The transport
// completes a handshake whose acknowledgement was lost when a datagram proves it
// (udp_handshake.hpp).
#include <enet/enet.h>

#include <boost/asio.hpp>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "server/host/transport.hpp"
#include "server/match/match.hpp"
#include "server/net/udp_connect_gate.hpp"
#include "server/net/udp_peer_connection.hpp"
#include "server/net/udp_refusal_log.hpp"

namespace arena::net {

struct udp_options {
    uint16_t port = 0;       // 0: any free port
    uint32_t max_peers = 0;  // ENet peer slots; 0: the match's connection limit (at most 4095)
    uint32_t peers_per_address = 64;
    size_t snapshot_budget = 1200;  // bytes: a snapshot larger than this is sent fragmented
    // Each snapshot datagram goes this many times, the copies a tick or more apart: a snapshot
    // is then missed only when every copy is lost (5 % loss: 0.25 % with 2), for that many
    // times the downstream bytes. 1: no copy. 0 (auto): per client, twice while the loss
    // measured from its acks is above about 1 %, else once (snapshot_loss.hpp).
    uint32_t snapshot_copies = 1;
    connect_gate_limits gate{};
    int64_t service_interval_ns = 10'000'000;  // ENet's resends and timeouts
    // A handshake not completed (CONNECT answered, VERIFY_CONNECT never acknowledged: what a
    // spoofed source leaves) holds a slot only while there is room: a connect that finds none
    // takes the slot of the oldest half-open handshake of the address holding the most, when
    // that address holds more than the connecting one (else it is refused: half_open).
    // A half-open peer is reset this long after it was first seen (ENet alone keeps it 30 s
    // and sends VERIFY_CONNECT 6 times); its VERIFY_CONNECT is never sent again, so a connect
    // that is not answered gets one 48-byte datagram back for its 52.
    int64_t half_open_timeout_ns = 1'000'000'000;
    // ENet's maximumWaitingData: bytes received from a peer and not yet handed to us (ENet's
    // default is 32 MiB). Four largest client frames.
    size_t max_waiting_bytes = 4 * (4 + 64 * 1024);
};

class udp_transport final : public host::transport {
public:
    udp_transport(host::transport_host& host, udp_options options);
    ~udp_transport() override;
    udp_transport(const udp_transport&) = delete;
    udp_transport& operator=(const udp_transport&) = delete;

    // Binds the server's --bind address and prints "udp listening on HOST:PORT". Throws when
    // ENet cannot bind.
    void start() override;
    uint64_t open_connections() const override { return connections_.size(); }
    // Its last words go out with ENet's disconnect, flushed at once (udp_peer_connection.cpp).
    bool drains_at_shutdown() const override { return false; }
    uint16_t port() const { return port_; }

    // For the peer connections.
    match::match& match_of(const match::connection& c);
    host::intake& intake();
    int64_t now_ns() const;
    void count_out(size_t bytes);
    void count_fragmented_snapshot();
    void count_snapshot_copy();
    size_t snapshot_budget() const { return options_.snapshot_budget; }
    uint32_t snapshot_copies() const { return options_.snapshot_copies; }
    int64_t tick_ns() const;
    // Sends what ENet queued once the current handler returns (one flush for a tick's fan-out).
    void flush_soon();
    void flush_now();

    size_t peers() const { return connections_.size(); }
    const connect_gate& gate() const { return gate_; }

private:
    void wait_readable();
    void arm_timer();
    void service();
    void on_connect(ENetPeer* peer);
    void on_receive(ENetPeer* peer, ENetPacket* packet);
    void on_disconnect(ENetPeer* peer);
    void reap_closing();
    void send_due_copies();  // the snapshot copies whose time came
    // Forgets a peer's connection; the host hears that it closed.
    std::map<uint64_t, std::unique_ptr<udp_peer_connection>>::iterator forget(
        std::map<uint64_t, std::unique_ptr<udp_peer_connection>>::iterator it);
    static int ENET_CALLBACK intercept(ENetHost* host, ENetEvent* event);
    // The datagram ENet just read: true to let ENet handle it; false refuses it (counted, and
    // logged at most once per reason per interval).
    bool admit(ENetHost* host);
    bool refuse(udp_refusal why, const std::string& address);
    // A datagram from a peer whose handshake ENet has not seen acknowledged, though the
    // datagram proves it arrived: gets the acknowledgement in front (udp_handshake.hpp).
    void acknowledge_proven_handshake(ENetHost* host);
    // Whether a connect from `from` may take a peer slot (a free one, or one a half-open
    // handshake gives up to it, reset here); the refusal otherwise.
    std::optional<udp_refusal> make_room_for_connect(ENetHost* host, const ENetAddress& from);
    // The refusal of a datagram to a peer by its commands (udp_peer_commands.hpp), if any.
    std::optional<udp_refusal> peer_commands_refusal(ENetHost* host);
    // Resets the peers whose handshake stayed half-open for half_open_timeout_ns, and keeps
    // ENet from sending their VERIFY_CONNECT again.
    void reap_half_open();

    boost::asio::io_context& io_;
    host::transport_host& owner_;  // the process host
    udp_options options_;
    ENetHost* host_ = nullptr;
    uint16_t port_ = 0;
    boost::asio::posix::stream_descriptor readable_;
    boost::asio::steady_timer timer_;
    connect_gate gate_;
    udp_refusal_log refusals_;
    std::vector<uint8_t> proven_handshake_;  // the datagram ENet reads instead, with its acknowledgement
    std::map<uint64_t, std::unique_ptr<udp_peer_connection>> connections_;  // by id, in connect order
    struct half_open_peer {
        enet_uint32 connect_id = 0;  // ENet's id of the handshake: a slot reused is a new one
        int64_t since_ns = -1;       // first seen half-open; -1: the slot is not half-open
    };
    std::vector<half_open_peer> half_open_;  // by peer slot
    uint64_t next_id_ = 1;
    bool flush_posted_ = false;
    bool stopped_ = false;
};

}  // namespace arena::net
