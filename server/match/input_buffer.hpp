#pragma once
// A player's inputs waiting for the world. Every tick consumes exactly one: the oldest waiting
// one, or the last one again when none waits (an underrun). A full buffer drops its oldest
// input (an overflow), so a client that runs ahead cannot build up latency.
#include <cstdint>
#include <deque>

#include "server/world/input.hpp"

namespace arena::match {

struct sequenced_input {
    uint32_t sequence = 0;
    world::player_input input{};
    uint64_t view = 0;  // the moment of the world the client showed, in 1/256 ticks; 0 = not told
};

class input_buffer {
public:
    explicit input_buffer(uint32_t capacity) : capacity_(capacity) {}

    void push(const sequenced_input& in) {
        if (waiting_.size() >= capacity_) {
            waiting_.pop_front();
            ++overflows_;
        }
        waiting_.push_back(in);
    }

    // The input for this tick. `last_consumed_sequence()` is the sequence it carried (unchanged
    // on an underrun: the client's input for this tick never came).
    world::player_input consume() {
        if (waiting_.empty()) {
            if (consumed_any_) ++underruns_;
            return last_.input;
        }
        last_ = waiting_.front();
        waiting_.pop_front();
        consumed_any_ = true;
        return last_.input;
    }

    uint32_t last_consumed_sequence() const { return last_.sequence; }
    // The view moment (1/256 ticks, 0 = not told) of the input consume() returned last.
    uint64_t last_consumed_view() const { return last_.view; }
    uint64_t underruns() const { return underruns_; }
    uint64_t overflows() const { return overflows_; }
    size_t waiting() const { return waiting_.size(); }

private:
    uint32_t capacity_;
    std::deque<sequenced_input> waiting_;
    sequenced_input last_{};
    bool consumed_any_ = false;
    uint64_t underruns_ = 0;
    uint64_t overflows_ = 0;
};

}  // namespace arena::match
