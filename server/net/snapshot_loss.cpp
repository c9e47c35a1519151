#include "server/net/snapshot_loss.hpp"

namespace arena::net {

void snapshot_loss::sent(uint32_t tick) {
    sent_[sent_count_ % sent_.size()] = tick;
    ++sent_count_;
    if (copies_ == 2 && --twice_left_ == 0) {
        copies_ = 1;
        snapshot_loss_ = limits_.copy_above;  // measured again from the threshold
    }
}

void snapshot_loss::acked(uint32_t tick) {
    if (tick <= last_ack_) return;  // the same ack again, or one overtaken by a newer input
    if (last_ack_ == 0) {           // the first: what came before it (the client starting) says nothing
        last_ack_ = tick;
        return;
    }
    // Every snapshot still remembered that was sent after the previous ack and before this
    // one was skipped: lost. The acknowledged one arrived, if it is one we sent.
    const uint64_t remembered = sent_count_ < sent_.size() ? sent_count_ : sent_.size();
    bool arrived = false;
    for (uint64_t i = sent_count_ - remembered; i < sent_count_; ++i) {
        const uint32_t t = sent_[i % sent_.size()];
        if (t > last_ack_ && t < tick) record(true);
        arrived = arrived || t == tick;
    }
    if (arrived) record(false);
    last_ack_ = tick;
}

void snapshot_loss::input_arrived(uint32_t sequence) {
    const bool skipped = last_input_ != 0 && sequence > last_input_ + 1;
    if (sequence > last_input_) last_input_ = sequence;
    if (!skipped || copies_ != 1 || had_copies_) return;
    // One lost snapshot would still bring the copies: the estimate has not yet decayed that far.
    if (snapshot_loss_ + limits_.smoothing * (1 - snapshot_loss_) > limits_.copy_above) start_copies();
}

void snapshot_loss::start_copies() {
    copies_ = 2;
    twice_left_ = limits_.copies_for_snapshots;
    had_copies_ = true;
}

void snapshot_loss::record(bool lost) {
    ++samples_;
    if (copies_ == 2) {
        if (lost) twice_left_ = limits_.copies_for_snapshots;  // both copies lost: the link is bad
        return;
    }
    snapshot_loss_ += limits_.smoothing * ((lost ? 1.0 : 0.0) - snapshot_loss_);
    if (snapshot_loss_ > limits_.copy_above) start_copies();
}

}  // namespace arena::net
