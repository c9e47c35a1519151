#include "client_sim/stats.hpp"

#include <algorithm>
#include <cmath>

namespace arena::bots {

double percentile_of_sorted(const std::vector<float>& sorted, double p) {
    if (sorted.empty()) return 0;
    const double n = static_cast<double>(sorted.size());
    // Rank in [1, n]: ceil(p/100 · n), at least 1 so that p = 0 gives the minimum.
    const double rank = std::clamp(std::ceil(p / 100.0 * n), 1.0, n);
    return sorted[static_cast<std::size_t>(rank) - 1];
}

summary sample_set::summarize() {
    summary s;
    s.count = values_.size();
    if (values_.empty()) return s;
    std::sort(values_.begin(), values_.end());
    s.mean = sum_ / static_cast<double>(values_.size());
    s.min = values_.front();
    s.p50 = percentile_of_sorted(values_, 50);
    s.p99 = percentile_of_sorted(values_, 99);
    s.max = values_.back();
    return s;
}

}  // namespace arena::bots
