#pragma once
// What a match says to its connections during a tick on a worker thread, kept in order
// instead of sent: a transport's connection belongs to the io thread (its buffers, its timers,
// its ENet host), so the host replays the outbox there once every match's tick is done
// (server/host/match_registry.hpp, --threads). A match that ticks on the io thread has none
// and calls its connections directly.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "protocol/messages.hpp"
#include "server/match/connection.hpp"

namespace arena::match {

class outbox {
public:
    void send(connection& to, protocol::frame_bytes frame);
    // Snapshots are copied: a shared encoder's frame is reused by the next tick.
    void send_snapshot(connection& to, const protocol::snapshot_encoder& snapshot, uint32_t ack_sequence);
    void send_snapshot_frame(connection& to, std::span<const uint8_t> frame);
    void close(connection& to, protocol::RejectCode code, std::string_view reason);

    // Each kept call, in the order it was made, to its connection; then none is kept.
    void deliver();
    [[nodiscard]] bool empty() const { return items_.empty(); }

private:
    enum class kind : uint8_t { control, snapshot, close };
    struct item {
        connection* to;
        kind what;
        protocol::frame_bytes bytes;  // the frame (control, snapshot)
        protocol::RejectCode code = protocol::RejectCode::bad_request;
        std::string reason{};  // close's
    };
    std::vector<item> items_;
};

}  // namespace arena::match
