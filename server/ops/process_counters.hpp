#pragma once
// The process's own figures, beside each match's (match_counters): its connections, the bytes
// and messages its transports moved, the ticks its loop dropped. One report() names them for
// --stats-json and /metrics (server/match/figures.hpp).
#include <cstdint>

#include "server/match/figures.hpp"

namespace arena::ops {

struct process_counters {
    uint64_t connections_open = 0;  // client connections now, joined or not
    uint64_t connections_peak = 0;  // most at once
    uint64_t bytes_in = 0;          // read from clients
    uint64_t bytes_out = 0;         // written to clients
    uint64_t messages_in = 0;       // verified protocol messages read
    uint64_t messages_out = 0;      // frames written
    uint64_t tick_overruns = 0;     // ticks dropped because the loop fell behind
};

void report(const process_counters& c, match::figure_sink& out);

}  // namespace arena::ops
