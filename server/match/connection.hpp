#pragma once
// How the match sees a client: a connection it was handed by a transport. It can send frames
// to it, replace its pending snapshot, close it with a last word, and name its peer. The match
// never touches a socket, so it is tested (and fuzzed, and simulated) without one. A
// transport (server/match/) implements this once per kind of link.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "protocol/messages.hpp"
#include "protocol/snapshot.hpp"

namespace arena::match {

struct client_record;  // what a match keeps of a connection it holds (match.hpp)

class connection {
public:
    connection() = default;
    // A copy is a new connection, held by no match yet: it takes the match key, not the record.
    connection(const connection& other) : match_key(other.match_key) {}
    connection& operator=(const connection& other) {
        match_key = other.match_key;
        return *this;
    }
    // Tells the match that holds it, if one does, that it is gone: a match that ends after its
    // connections (a test's, or at exit) must not write to them (connection.cpp).
    virtual ~connection();
    // A control message (Welcome, Pong, Reject, Bye): always delivered, in order.
    virtual void send(protocol::frame_bytes frame) = 0;
    // The newest snapshot with this client's ack: replaces one that is still unsent.
    virtual void send_snapshot(const protocol::snapshot_encoder& snapshot, uint32_t ack_sequence) = 0;
    // A snapshot frame built for this client alone (a delta, or its own view): copied, and
    // replaces one that is still unsent, as above.
    virtual void send_snapshot_frame(std::span<const uint8_t> frame) = 0;
    // Sends Reject(code, reason) as the last word, then closes.
    virtual void close(protocol::RejectCode code, std::string_view reason) = 0;
    // Sends Bye(reason) as the last word, then closes (another connection took this player
    // over, the server shuts down).
    virtual void close_with_bye(std::string_view reason) = 0;
    // Bytes a snapshot frame to this client may take (delta clients; a larger view is trimmed
    // by priority, snapshot_fanout.hpp); 0: no limit. A datagram transport sets its datagram
    // budget; a stream has none.
    virtual size_t snapshot_budget() const { return 0; }
    // The same Bye carrying the end of the match: the winner and the final scoreboard
    // (protocol Bye.match_over). A transport that cannot send it yet sends the plain Bye.
    virtual void close_with_result(std::string_view reason, const protocol::match_result& /*result*/) {
        close_with_bye(reason);
    }
    // The peer's address as the logs show it ("127.0.0.1:52814"; "" when unknown).
    virtual std::string_view peer() const = 0;
    // The peer's address without its port ("127.0.0.1", "::1"): handshake slots are shared
    // fairly between addresses. By default peer() up to its last ':'.
    virtual std::string_view address() const {
        const std::string_view p = peer();
        const size_t colon = p.rfind(':');
        return colon == std::string_view::npos ? p : p.substr(0, colon);
    }

    // Which of the process's matches this connection belongs to, as the host's match registry
    // numbers them (server/host/match_registry.hpp): 0, the default match, until a Hello moves
    // it. The registry alone reads and writes it; a match never looks at it.
    uint64_t match_key = 0;
    // The record of this connection in the match that holds it; null while none does. That
    // match alone sets it (connect) and clears it (when it forgets the connection, and when it
    // ends before the connection), so that each message finds its client without a search.
    // Mutable: the match's bookkeeping, not the connection's state.
    mutable client_record* record = nullptr;
};

}  // namespace arena::match
