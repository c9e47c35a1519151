#pragma once
// The standard process_* figures every Prometheus client library exports, read from
// /proc/self (Linux only; elsewhere they stay zero and `available` false).
#include <cstdint>
#include <string_view>

namespace arena::ops {

struct process_stats {
    bool available = false;
    double resident_memory_bytes = 0;  // bytes
    double virtual_memory_bytes = 0;   // bytes
    double cpu_seconds = 0;            // user + system, seconds
    double start_time_seconds = 0;     // since the Unix epoch, seconds
    double open_fds = 0;
    double max_fds = 0;  // soft RLIMIT_NOFILE
};

process_stats read_process_stats();

// The pieces read_process_stats() parses, separate so that tests can feed them fixed text.
// /proc/self/stat: utime, stime (fields 14, 15) and starttime (22), in clock ticks.
struct proc_stat_fields {
    uint64_t utime_ticks = 0;
    uint64_t stime_ticks = 0;
    uint64_t start_ticks = 0;  // since boot
};
bool parse_proc_self_stat(std::string_view text, proc_stat_fields& out);
// /proc/stat: "btime SECONDS", the boot time since the epoch; 0 when missing.
uint64_t parse_boot_time(std::string_view text);

}  // namespace arena::ops
