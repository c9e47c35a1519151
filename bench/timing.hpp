#pragma once
// Timing helpers shared by the benchmarks: a steady clock, per-sample statistics (median and
// p90 by nearest rank, as ../shared/peers/box2d/bench_scene.hpp computes them) and the machine
// description printed with every result.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace arena::bench {

using clock = std::chrono::steady_clock;

inline double ms_between(clock::time_point t0, clock::time_point t1) {
    return std::chrono::duration<double, std::milli>(t1 - t0).count();
}

struct stats {
    double median = 0;  // ms
    double p90 = 0;     // ms
    double min = 0;     // ms
    double mean = 0;    // ms
};

// Nearest-rank percentiles of per-sample times in ms.
inline stats summarize(std::vector<double> ms) {
    stats s;
    if (ms.empty()) return s;
    std::sort(ms.begin(), ms.end());
    const size_t n = ms.size();
    s.median = (n % 2) ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
    s.p90 = ms[std::min(n - 1, static_cast<size_t>(std::ceil(0.9 * static_cast<double>(n))) - 1)];
    s.min = ms.front();
    double sum = 0;
    for (double v : ms) sum += v;
    s.mean = sum / static_cast<double>(n);
    return s;
}

// Times `fn` once per sample after `warmup` untimed calls.
template <class Fn>
stats time_samples(int warmup, int samples, Fn&& fn) {
    for (int k = 0; k < warmup; ++k) fn();
    std::vector<double> ms;
    ms.reserve(static_cast<size_t>(samples));
    for (int k = 0; k < samples; ++k) {
        const auto t0 = clock::now();
        fn();
        ms.push_back(ms_between(t0, clock::now()));
    }
    return summarize(std::move(ms));
}

}  // namespace arena::bench
