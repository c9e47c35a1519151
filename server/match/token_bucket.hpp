#pragma once
// A rate limit in real time that allows a burst: `capacity` tokens, refilled at `rate` per
// second of the times it is given, one taken per event. Counting events per second of ticks
// instead dropped every honest player after the server itself paused: the inputs that had
// queued in the kernel arrived together. The caller hands the time in (the transport's arrival
// time), so the match still reads no clock.
#include <algorithm>
#include <cstdint>

namespace arena::match {

struct token_bucket {
    double tokens = 0;
    int64_t refilled_ns = 0;  // the time `tokens` was last brought up to date
    bool started = false;     // the first event finds the bucket full

    // Takes one token at `now_ns`; false when there is none (the event is over the limit).
    // A time earlier than the last one (two clocks, a reordering) refills nothing.
    bool take(int64_t now_ns, double rate, double capacity) {
        if (!started) {
            started = true;
            tokens = capacity;
            refilled_ns = now_ns;
        } else if (now_ns > refilled_ns) {
            tokens = std::min(capacity, tokens + static_cast<double>(now_ns - refilled_ns) * 1e-9 * rate);
            refilled_ns = now_ns;
        }
        if (tokens < 1) return false;
        tokens -= 1;
        return true;
    }
};

}  // namespace arena::match
