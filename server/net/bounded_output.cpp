#include "server/net/bounded_output.hpp"

#include <utility>

namespace arena::net {

bool bounded_output::push_control(protocol::frame_bytes frame, int64_t now_ns) {
    if (control_.size() >= max_control_frames_) return false;
    control_.push_back(std::move(frame));
    started_waiting(now_ns);
    return true;
}

void bounded_output::put_snapshot(const protocol::snapshot_encoder& snapshot, uint32_t ack_sequence, int64_t now_ns) {
    snapshot.copy_with_ack(ack_sequence, snapshot_next_);
    snapshot_pending_ = true;
    started_waiting(now_ns);
}

void bounded_output::put_snapshot_frame(std::span<const uint8_t> frame, int64_t now_ns) {
    snapshot_next_.assign(frame.begin(), frame.end());
    snapshot_pending_ = true;
    started_waiting(now_ns);
}

void bounded_output::keep_only(protocol::frame_bytes last) {
    control_.clear();
    snapshot_pending_ = false;
    control_.push_back(std::move(last));
}

std::optional<std::span<const uint8_t>> bounded_output::next() {
    if (!control_.empty()) {
        control_writing_ = std::move(control_.front());
        control_.pop_front();
        return std::span<const uint8_t>(control_writing_);
    }
    if (snapshot_pending_) {
        std::swap(snapshot_next_, snapshot_writing_);
        snapshot_pending_ = false;
        return std::span<const uint8_t>(snapshot_writing_);
    }
    waiting_since_ns_ = 0;
    return std::nullopt;
}

const std::vector<std::span<const uint8_t>>& bounded_output::take_all() {
    batch_.clear();
    controls_writing_.clear();
    while (!control_.empty()) {
        controls_writing_.push_back(std::move(control_.front()));
        control_.pop_front();
    }
    for (const protocol::frame_bytes& frame : controls_writing_)
        if (!frame.empty()) batch_.emplace_back(frame);
    if (snapshot_pending_) {
        std::swap(snapshot_next_, snapshot_writing_);
        snapshot_pending_ = false;
        batch_.emplace_back(snapshot_writing_);
    }
    if (batch_.empty()) waiting_since_ns_ = 0;
    return batch_;
}

void bounded_output::written(int64_t now_ns) {
    waiting_since_ns_ = waiting() ? now_ns : 0;
}

void bounded_output::started_waiting(int64_t now_ns) {
    if (waiting_since_ns_ == 0) waiting_since_ns_ = now_ns;
}

}  // namespace arena::net
