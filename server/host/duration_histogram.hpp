#pragma once
// Tick durations in fixed 10 µs buckets up to 100 ms (and an exact maximum): constant memory
// however long the server runs, percentiles to 10 µs.
#include <algorithm>
#include <array>
#include <cstdint>

namespace arena::host {

class duration_histogram {
public:
    static constexpr int64_t bucket_ns = 10'000;
    static constexpr size_t bucket_count = 10'000;

    void add(int64_t ns) {
        const size_t bucket =
            std::min<size_t>(static_cast<size_t>(std::max<int64_t>(ns, 0) / bucket_ns), bucket_count - 1);
        ++buckets_[bucket];
        ++count_;
        max_ns_ = std::max(max_ns_, ns);
        sum_ns_ += ns;
    }

    // Upper edge of the bucket holding the q-quantile (q in [0, 1]), capped by the maximum.
    int64_t quantile_ns(double q) const {
        if (count_ == 0) return 0;
        const uint64_t rank = std::max<uint64_t>(1, static_cast<uint64_t>(q * static_cast<double>(count_) + 0.999999));
        uint64_t seen = 0;
        for (size_t i = 0; i < bucket_count; ++i) {
            seen += buckets_[i];
            if (seen >= rank) return std::min<int64_t>(static_cast<int64_t>(i + 1) * bucket_ns, max_ns_);
        }
        return max_ns_;
    }

    uint64_t count() const { return count_; }
    int64_t max_ns() const { return max_ns_; }
    double mean_ns() const { return count_ ? static_cast<double>(sum_ns_) / static_cast<double>(count_) : 0; }
    void clear() { *this = duration_histogram{}; }

private:
    std::array<uint32_t, bucket_count> buckets_{};
    uint64_t count_ = 0;
    int64_t max_ns_ = 0;
    int64_t sum_ns_ = 0;
};

}  // namespace arena::host
