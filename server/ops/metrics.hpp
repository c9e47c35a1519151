#pragma once
// What the server reports to Prometheus, and its rendering in the text exposition format. The
// counters come from the match's and the process's report() (one list of figures for the
// stats and /metrics); the tick histogram, the lifecycle and /proc figures are added here. No
// Asio and no clock: render_metrics is a pure function.
//
// Naming (https://prometheus.io/docs/practices/naming/): the arena_ prefix, base units
// (seconds, bytes), _total on counters. No player ids or names as labels: a label value makes
// a new time series, and players come and go by the thousand.
#include <cstdint>
#include <functional>
#include <string>

#include "server/match/figures.hpp"
#include "server/ops/histogram.hpp"
#include "server/ops/process_stats.hpp"

namespace arena::ops {

struct server_metrics {
    // Tick loop.
    histogram tick_duration_s{tick_duration_buckets_s()};  // seconds per world step
    double tick_budget_s = 0;                              // 1 / tick rate, seconds
    // Every counter and gauge of the match and the process, through their report()s.
    std::function<void(match::figure_sink&)> figures;
    // Lifecycle.
    bool draining = false;  // shutting down: no new players
    std::string version;    // build version; "" renders the compiled-in one
    process_stats process;  // filled by render's caller (read_process_stats)
};

// The version this binary was built as (CMake's PROJECT_VERSION).
const char* build_version();

// The whole /metrics body.
std::string render_metrics(const server_metrics& m);

// The Content-Type of that body.
inline constexpr const char* metrics_content_type = "text/plain; version=0.0.4; charset=utf-8";

}  // namespace arena::ops
