#pragma once
// The one way in for what a client sends, once its transport has cut the bytes into frames:
// verify the frame (protocol::verify_message with the client limits), count it, hand it to the
// connection's match (match_registry.hpp), or refuse it through that match (a Reject with the
// reason, which the match counts and logs). TCP, UDP, WebSocket and the tests' simulated network
// all come through here, so what a client may send is checked in one place. No sockets and no
// clock: a transport passes the arrival time in.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "protocol/framing.hpp"
#include "server/host/match_registry.hpp"
#include "server/ops/process_counters.hpp"

namespace arena::host {

struct intake_result {
    // False: the connection is over, refused (its Reject is queued) or it said Bye; the
    // transport closes it once its last word is out.
    bool go_on = false;
    // The verified message the match was handed (it lives as long as the frame); null when the
    // frame was refused before the match read it.
    const protocol::Message* message = nullptr;
};

class intake {
public:
    // Both outlive the intake; `counters` are the process's (bytes_in, messages_in).
    intake(match_registry& matches, ops::process_counters& counters);

    // One whole frame from `from` (8-byte aligned, as protocol::frame_reader keeps it) that
    // arrived at `arrival_ns` (the transport's steady clock, ns); nullopt: at the match's current
    // tick time (a transport without a clock: the simulated network).
    // `held_ns`: how long the bytes waited in the kernel before they were read (-1: unknown),
    // which a Pong reports.
    intake_result take(match::connection& from, std::span<const uint8_t> frame, std::optional<int64_t> arrival_ns,
                       int64_t held_ns = -1);
    // Bytes from `from` that its frame reader could not frame (reader.failed()).
    void refuse_unreadable(match::connection& from, const protocol::frame_reader& reader);
    // A refusal a transport finds in its own framing: a datagram or a WebSocket message that is
    // not exactly one frame, a text message, a message over the size limit.
    void refuse(match::connection& from, const match::rejection& why);
    // Bytes read from a client, before framing.
    void count_bytes(size_t bytes) { counters_.bytes_in += bytes; }

    match_registry& matches() { return matches_; }

private:
    match_registry& matches_;
    ops::process_counters& counters_;
};

}  // namespace arena::host
