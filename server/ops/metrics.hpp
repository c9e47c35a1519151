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
#include <map>
#include <string>

#include "server/match/figures.hpp"
#include "server/ops/histogram.hpp"
#include "server/ops/process_stats.hpp"

namespace arena::ops {

// One mode's matches now (labels by mode only, never by match id: a bounded number of series).
struct mode_figures {
    uint64_t matches = 0;
    uint64_t players = 0;                                  // with a live connection, in every match of the mode
    histogram tick_duration_s{tick_duration_buckets_s()};  // one match's step, seconds
    uint64_t ticks_late = 0;                               // match ticks run more than a tick interval late, whole run
    uint64_t ticks_dropped = 0;  // match ticks given up because the process fell behind, whole run
};

struct server_metrics {
    // Tick loop.
    histogram tick_duration_s{tick_duration_buckets_s()};  // seconds per world step
    double tick_budget_s = 0;                              // 1 / tick rate, seconds
    // By mode: arena_matches, arena_players, arena_match_tick_duration_seconds,
    // arena_match_ticks_late_total, arena_match_ticks_dropped_total.
    std::map<std::string, mode_figures> modes;
    // Every counter and gauge of the default match and the process, through their report()s.
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
