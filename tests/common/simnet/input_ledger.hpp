#pragma once
// What the match must do with one player's inputs, written as the rule itself: an input whose
// sequence is not above the last one received is ignored (a duplicate, or overtaken); the
// others wait in order, at most `capacity` of them (a full buffer drops its oldest); each tick
// consumes the oldest waiting one, exactly once, or repeats the last when none waits. A test
// feeds it what the match was given and compares what the match did with it, tick by tick.
#include <cstdint>
#include <deque>

#include "protocol/messages.hpp"
#include "server/world/input.hpp"

namespace arena::simnet {

class input_ledger {
public:
    explicit input_ledger(std::uint32_t capacity) : capacity_(capacity) {}

    void received(const protocol::input_msg& in) {
        if (in.sequence <= last_received_) {
            ++stale_;
            return;
        }
        // Earlier inputs repeated in it (Input.earlier) that were not received yet come first,
        // in order.
        for (const protocol::earlier_input& e : in.earlier) {
            if (e.sequence <= last_received_) continue;
            take({e.sequence, e.thrust, e.turn, e.buttons, in.snapshot_ack, {}});
            ++recovered_;
        }
        take(in);
    }

    [[nodiscard]] std::uint64_t recovered() const { return recovered_; }

private:
    void take(const protocol::input_msg& in) {
        last_received_ = in.sequence;
        ++accepted_;
        if (waiting_.size() >= capacity_) {
            waiting_.pop_front();
            ++overflows_;
        }
        waiting_.push_back(in);
    }

public:
    // This tick's input, as the match must have applied it.
    world::player_input consume() {
        if (waiting_.empty()) {
            if (consumed_ > 0) ++underruns_;
            return current_;
        }
        const protocol::input_msg& next = waiting_.front();
        consumed_sequence_ = next.sequence;
        current_ = {next.thrust, next.turn, next.buttons};
        ++consumed_;
        waiting_.pop_front();
        return current_;
    }

    // The sequence of the input consumed last: every snapshot's ack must be this.
    [[nodiscard]] std::uint32_t consumed_sequence() const { return consumed_sequence_; }
    [[nodiscard]] std::uint64_t consumed() const { return consumed_; }
    [[nodiscard]] std::uint64_t overflows() const { return overflows_; }
    [[nodiscard]] std::uint64_t underruns() const { return underruns_; }
    [[nodiscard]] std::uint64_t stale() const { return stale_; }
    [[nodiscard]] std::size_t waiting() const { return waiting_.size(); }
    [[nodiscard]] std::uint32_t last_received() const { return last_received_; }
    // Inputs received that were not stale.
    [[nodiscard]] std::uint64_t accepted() const { return accepted_; }

private:
    std::uint32_t capacity_;
    std::deque<protocol::input_msg> waiting_;
    std::uint32_t last_received_ = 0;
    std::uint32_t consumed_sequence_ = 0;
    world::player_input current_{};
    std::uint64_t accepted_ = 0;
    std::uint64_t consumed_ = 0;
    std::uint64_t overflows_ = 0;
    std::uint64_t underruns_ = 0;
    std::uint64_t stale_ = 0;
    std::uint64_t recovered_ = 0;
};

}  // namespace arena::simnet
