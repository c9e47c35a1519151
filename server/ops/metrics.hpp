#pragma once
// What the server reports to Prometheus, as a plain struct the server fills, and its rendering
// in the text exposition format. No Asio and no clock: render_metrics is a pure function.
//
// Naming (https://prometheus.io/docs/practices/naming/): the arena_ prefix, base units
// (seconds, bytes), _total on counters. No player ids or names as labels: a label value makes
// a new time series, and players come and go by the thousand.
#include <cstdint>
#include <map>
#include <string>

#include "server/ops/histogram.hpp"
#include "server/ops/process_stats.hpp"

namespace arena::ops {

struct server_metrics {
    // Tick loop.
    histogram tick_duration_s{tick_duration_buckets_s()};  // seconds per world step
    uint64_t ticks = 0;                                    // world steps so far
    uint64_t tick_overruns = 0;                            // ticks dropped because the loop fell behind
    double tick_budget_s = 0;                              // 1 / tick rate, seconds
    // Players and connections.
    uint64_t players_connected = 0;
    uint64_t players_max = 0;       // --max-players
    uint64_t connections_open = 0;  // sockets, including those not (yet) joined
    uint64_t joins = 0;
    uint64_t leaves = 0;
    std::map<std::string, uint64_t> rejects;  // by reason code name (protocol RejectCode)
    // Traffic, whole run.
    uint64_t bytes_in = 0;
    uint64_t bytes_out = 0;
    uint64_t messages_in = 0;
    uint64_t messages_out = 0;
    // Snapshots.
    uint64_t snapshots_sent = 0;       // one per client per broadcast
    uint64_t snapshot_size_bytes = 0;  // the last snapshot frame built, bytes
    // Input buffers, all players (departed ones included).
    uint64_t inputs_received = 0;
    uint64_t input_underruns = 0;  // a tick found no input and repeated the last one
    uint64_t input_overflows = 0;  // an input arrived to a full buffer; the oldest went
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
