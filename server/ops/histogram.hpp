#pragma once
// A Prometheus-style histogram: fixed upper bounds chosen up front, a count per bucket, a sum
// and a count. Constant memory however long the server runs; no clock and no Asio, so the
// server can observe into it from its tick loop and render it later.
#include <algorithm>
#include <cstdint>
#include <vector>

namespace arena::ops {

// Tick durations in seconds, around the 16.7 ms budget of a 60 Hz tick: the low buckets show
// how much headroom a healthy tick has, the high ones how badly an overrun missed.
inline const std::vector<double>& tick_duration_buckets_s() {
    static const std::vector<double> bounds = {0.0005, 0.001, 0.002, 0.004, 0.008, 0.0166, 0.033, 0.1};
    return bounds;
}

class histogram {
public:
    // upper_bounds: increasing, finite; the +Inf bucket is implicit.
    explicit histogram(std::vector<double> upper_bounds = tick_duration_buckets_s())
        : bounds_(std::move(upper_bounds)), counts_(bounds_.size() + 1, 0) {}

    void observe(double value) {
        // First bucket whose bound is >= value (Prometheus buckets are "less than or equal").
        const auto it = std::lower_bound(bounds_.begin(), bounds_.end(), value);
        ++counts_[static_cast<size_t>(it - bounds_.begin())];
        sum_ += value;
        ++count_;
    }

    const std::vector<double>& upper_bounds() const { return bounds_; }
    // Per bucket, not cumulative; the last entry is the +Inf bucket.
    const std::vector<uint64_t>& bucket_counts() const { return counts_; }
    double sum() const { return sum_; }
    uint64_t count() const { return count_; }

private:
    std::vector<double> bounds_;
    std::vector<uint64_t> counts_;
    double sum_ = 0;
    uint64_t count_ = 0;
};

}  // namespace arena::ops
