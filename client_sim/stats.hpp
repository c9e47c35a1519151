#pragma once
// Samples of one figure (RTT, snapshot gap, prediction error, ...) and their summary: count,
// mean, min, p50, p99, max. Values are kept, not binned, so percentiles are exact: at 1000
// bots × 20 snapshots/s a minute of snapshot gaps is 1.2 M floats (4.8 MB), affordable.
#include <cstddef>
#include <vector>

namespace arena::bots {

struct summary {
    std::size_t count = 0;
    double mean = 0;
    double min = 0;
    double p50 = 0;
    double p99 = 0;
    double max = 0;
};

// The nearest-rank percentile of sorted values: the smallest value with at least p % of the
// values at or below it (p in [0, 100]). 0 when empty. Nearest rank, not interpolation, so
// that every reported figure is a value that was actually measured.
double percentile_of_sorted(const std::vector<float>& sorted, double p);

class sample_set {
public:
    void add(double value) {
        values_.push_back(static_cast<float>(value));
        sum_ += value;
    }
    // Keeps the capacity: the per-second windows are cleared every second.
    void clear() {
        values_.clear();
        sum_ = 0;
    }
    void reserve(std::size_t n) { values_.reserve(n); }
    [[nodiscard]] std::size_t size() const { return values_.size(); }
    [[nodiscard]] bool empty() const { return values_.empty(); }

    // Sorts the values in place (their order carries no meaning) and summarises them.
    summary summarize();

private:
    std::vector<float> values_;
    double sum_ = 0;  // double: a million float samples summed in float would lose digits
};

}  // namespace arena::bots
