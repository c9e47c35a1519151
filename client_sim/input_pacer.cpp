#include "client_sim/input_pacer.hpp"

namespace arena::bots {

void input_pacer::on_snapshot(std::uint32_t ack_sequence, std::uint16_t extra_inputs_waiting) {
    // A snapshot taken before the last gap reached the server still shows the old queue.
    if (ack_sequence < counts_from_) return;
    seen_ = extra_inputs_waiting > 0 ? seen_ + 1 : 0;
    if (seen_ >= settle_snapshots) {
        leave_out_ = true;
        seen_ = 0;
    }
}

bool input_pacer::send_this_tick(std::uint32_t next_sequence) {
    if (!leave_out_) return true;
    leave_out_ = false;
    ++left_out_;
    counts_from_ = next_sequence;  // the input after the gap: its ack shows the queue after it
    return false;
}

}  // namespace arena::bots
