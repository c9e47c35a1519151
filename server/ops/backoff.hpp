#pragma once
// Exponential backoff for retrying a sidecar that is not up yet: initial, doubling, capped.
// No jitter: one server talks to one sidecar on its own pod, so there is no herd to spread.
#include <algorithm>
#include <cstdint>

namespace arena::ops {

class backoff {
public:
    backoff(int64_t initial_ns, int64_t max_ns) : initial_ns_(initial_ns), max_ns_(max_ns), next_ns_(initial_ns) {}

    // The wait before the next attempt; each call doubles the one after, up to the cap.
    int64_t next_ns() {
        const int64_t wait = next_ns_;
        next_ns_ = std::min(max_ns_, next_ns_ * 2);
        return wait;
    }
    void reset() { next_ns_ = initial_ns_; }

private:
    int64_t initial_ns_;
    int64_t max_ns_;
    int64_t next_ns_;
};

}  // namespace arena::ops
