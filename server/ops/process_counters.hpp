#pragma once
// The process's own figures, beside each match's (match_counters): its connections, the bytes
// and messages its transports moved, the ticks its loop dropped, and the last stats window's
// tick times and traffic. One report() names them for --stats-json, /metrics and the stats log
// line (server/match/figures.hpp).
#include <cstdint>
#include <map>
#include <string>

#include "server/match/figures.hpp"

namespace arena::ops {

// Since the last stats log line: only that line shows them (the whole run's tick times are the
// /metrics histogram and the --stats-json tick_ms, its traffic the byte counters).
struct stats_window {
    double tick_ms_p50 = 0;  // world step time, ms
    double tick_ms_p99 = 0;
    double tick_ms_max = 0;
    double bytes_in_per_s = 0;   // read from clients
    double bytes_out_per_s = 0;  // written to clients
};

struct process_counters {
    uint64_t connections_open = 0;                // client connections now, joined or not, TCP and UDP
    uint64_t connections_peak = 0;                // most at once
    uint64_t bytes_in = 0;                        // read from clients
    uint64_t bytes_out = 0;                       // written to clients
    uint64_t messages_in = 0;                     // verified protocol messages read
    uint64_t messages_out = 0;                    // frames written
    uint64_t tick_overruns = 0;                   // ticks dropped because the loop fell behind
    uint64_t snapshots_fragmented = 0;            // UDP snapshots over the datagram budget, sent as fragments
    uint64_t snapshot_copies = 0;                 // UDP snapshot datagrams sent again (--udp-snapshot-copies)
    std::map<std::string, uint64_t> udp_refused;  // datagrams refused before ENet read them, by reason
    stats_window window;                          // filled for the stats log line only
};

void report(const process_counters& c, match::figure_sink& out);

}  // namespace arena::ops
