#pragma once
// What a stream connection (a TCP session, a WebSocket session) has waiting to be written, kept
// bounded: control frames (Welcome, Pong, Reject, game frames) in order up to a limit, and one
// snapshot slot that a newer snapshot replaces, so a client that does not read costs at most
// one snapshot and a few small frames. It also keeps when output began to wait unwritten, which
// the server's stall check reads. No I/O: the connection's writer asks it what to write next.
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <vector>

#include "protocol/messages.hpp"
#include "protocol/snapshot.hpp"

namespace arena::net {

class bounded_output {
public:
    explicit bounded_output(std::size_t max_control_frames) : max_control_frames_(max_control_frames) {}

    // Queues a control frame. False: the limit is reached and nothing was queued (the client
    // is not reading: the caller refuses it as a slow consumer).
    [[nodiscard]] bool push_control(protocol::frame_bytes frame, int64_t now_ns);
    // Puts a snapshot in the slot, replacing one not yet being written.
    void put_snapshot(const protocol::snapshot_encoder& snapshot, uint32_t ack_sequence, int64_t now_ns);
    void put_snapshot_frame(std::span<const uint8_t> frame, int64_t now_ns);
    // Drops whatever waits: `last` (a Reject, a Bye, or empty for nothing) is all that is left.
    void keep_only(protocol::frame_bytes last);

    // The next bytes to write (control frames first, in order, then the snapshot), valid until
    // the next call; empty bytes stand for nothing to write. Nothing: the output is drained.
    [[nodiscard]] std::optional<std::span<const uint8_t>> next();
    // Every frame waiting, in the same order (control frames, then the snapshot), for one
    // gathered write; valid until the next take_all() or next(). Frames with no bytes (a close
    // without a last word) are left out. Empty: the output is drained.
    [[nodiscard]] const std::vector<std::span<const uint8_t>>& take_all();
    // The bytes next() or take_all() gave were written: progress, so the stall clock starts
    // again if more waits.
    void written(int64_t now_ns);
    // Nanoseconds output has waited without a byte written (0 when nothing waits).
    [[nodiscard]] int64_t stalled_ns(int64_t now_ns) const {
        return waiting_since_ns_ == 0 ? 0 : now_ns - waiting_since_ns_;
    }

private:
    [[nodiscard]] bool waiting() const { return !control_.empty() || snapshot_pending_; }
    void started_waiting(int64_t now_ns);

    std::size_t max_control_frames_;
    std::deque<protocol::frame_bytes> control_;  // in order, bounded
    protocol::frame_bytes control_writing_;
    std::vector<protocol::frame_bytes> controls_writing_;  // take_all()'s control frames
    std::vector<std::span<const uint8_t>> batch_;          // take_all()'s result
    std::vector<uint8_t> snapshot_next_;                   // newest snapshot not yet being written
    std::vector<uint8_t> snapshot_writing_;
    bool snapshot_pending_ = false;
    int64_t waiting_since_ns_ = 0;  // when output began to wait unwritten; 0 = nothing waits
};

}  // namespace arena::net
