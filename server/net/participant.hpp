#pragma once
// How the game sees a connected client: something it can send frames to. The game never
// touches a socket, so it is tested without one.
#include <cstdint>
#include <span>
#include <string_view>

#include "protocol/messages.hpp"
#include "protocol/snapshot.hpp"

namespace arena::net {

class participant {
public:
    virtual ~participant() = default;
    // A control message (Welcome, Pong, Reject, Bye): always delivered, in order.
    virtual void send(protocol::frame_bytes frame) = 0;
    // The newest snapshot with this client's ack: replaces one that is still unsent.
    virtual void send_snapshot(const protocol::snapshot_encoder& snapshot, uint32_t ack_sequence) = 0;
    // A snapshot frame built for this client alone (a delta, or its own view): copied, and
    // replaces one that is still unsent, as above.
    virtual void send_snapshot_frame(std::span<const uint8_t> frame) = 0;
    // Sends `code` and `reason` as a Reject (or a Bye when joined), then closes.
    virtual void reject(protocol::RejectCode code, std::string_view reason) = 0;
    // Sends Bye(reason) and closes (another connection took this player over).
    virtual void say_bye(std::string_view reason) = 0;
};

}  // namespace arena::net
