#pragma once
// The fixed-step clock of the tick loop: integer nanoseconds and an accumulator, so time never
// drifts and Δt never scales. When the loop falls behind it runs at most `max_catch_up` ticks
// at once and drops the rest as overruns: no spiral of death. No clock is read here: the
// caller passes the time in, so it is tested in virtual time.
#include <cstdint>

namespace arena::host {

class tick_clock {
public:
    tick_clock(int64_t tick_ns, uint32_t max_catch_up) : tick_ns_(tick_ns), max_catch_up_(max_catch_up) {}

    // Starts counting at `now_ns`.
    void start(int64_t now_ns) {
        last_ns_ = now_ns;
        accumulator_ns_ = 0;
    }

    // How many ticks are due at `now_ns`; ticks beyond max_catch_up are dropped and counted.
    uint32_t advance(int64_t now_ns) {
        if (now_ns > last_ns_) accumulator_ns_ += now_ns - last_ns_;
        last_ns_ = now_ns;
        int64_t due = accumulator_ns_ / tick_ns_;
        if (due > static_cast<int64_t>(max_catch_up_)) {
            overruns_ += static_cast<uint64_t>(due - max_catch_up_);
            due = max_catch_up_;
            accumulator_ns_ = due * tick_ns_ + accumulator_ns_ % tick_ns_;
        }
        accumulator_ns_ -= due * tick_ns_;
        return static_cast<uint32_t>(due);
    }

    // When the next tick falls due.
    int64_t next_due_ns() const { return last_ns_ + (tick_ns_ - accumulator_ns_); }

    uint64_t overruns() const { return overruns_; }
    int64_t tick_ns() const { return tick_ns_; }

private:
    int64_t tick_ns_;
    uint32_t max_catch_up_;
    int64_t last_ns_ = 0;
    int64_t accumulator_ns_ = 0;
    uint64_t overruns_ = 0;
};

}  // namespace arena::host
