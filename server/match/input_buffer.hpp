#pragma once
// A player's inputs waiting for the world. Every tick consumes exactly one: the oldest waiting
// one, or the last one again when none waits (an underrun). A full buffer drops its oldest
// input (an overflow), so a client that runs ahead cannot build up latency.
//
// A ring over storage allocated once: a push is a store into memory the player already owns
// (a deque allocated and freed a block every few dozen inputs, and its bookkeeping was a
// cache miss of its own on every Input).
#include <cstdint>
#include <vector>

#include "server/world/input.hpp"

namespace arena::match {

struct sequenced_input {
    uint32_t sequence = 0;
    world::player_input input{};
    uint64_t view = 0;  // the moment of the world the client showed, in 1/256 ticks; 0 = not told
};

class input_buffer {
public:
    explicit input_buffer(uint32_t capacity) : slots_(capacity == 0 ? 1 : capacity) {}

    void push(const sequenced_input& in) {
        if (count_ == slots_.size()) {
            head_ = wrap(head_ + 1);
            --count_;
            ++overflows_;
        }
        slots_[wrap(head_ + count_)] = in;
        ++count_;
    }

    // The input for this tick. `last_consumed_sequence()` is the sequence it carried (unchanged
    // on an underrun: the client's input for this tick never came).
    world::player_input consume() {
        if (count_ == 0) {
            if (consumed_any_) ++underruns_;
            return last_.input;
        }
        last_ = slots_[head_];
        head_ = wrap(head_ + 1);
        --count_;
        consumed_any_ = true;
        return last_.input;
    }

    uint32_t last_consumed_sequence() const { return last_.sequence; }
    // The view moment (1/256 ticks, 0 = not told) of the input consume() returned last.
    uint64_t last_consumed_view() const { return last_.view; }
    uint64_t underruns() const { return underruns_; }
    uint64_t overflows() const { return overflows_; }
    size_t waiting() const { return count_; }
    // Where the next push writes: a transport may fetch it into the cache ahead of the Input.
    const sequenced_input* next_slot() const { return &slots_[wrap(head_ + count_)]; }

private:
    // An index one lap past the end at most (head_ + count_ ≤ 2 × capacity − 1).
    size_t wrap(size_t i) const { return i >= slots_.size() ? i - slots_.size() : i; }

    std::vector<sequenced_input> slots_;
    size_t head_ = 0;   // the oldest waiting input
    size_t count_ = 0;  // how many wait
    sequenced_input last_{};
    bool consumed_any_ = false;
    uint64_t underruns_ = 0;
    uint64_t overflows_ = 0;
};

}  // namespace arena::match
