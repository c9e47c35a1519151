#include "server/ops/process_stats.hpp"

#include <dirent.h>
#include <sys/resource.h>
#include <unistd.h>

#include <charconv>
#include <fstream>
#include <sstream>
#include <string>

namespace arena::ops {

namespace {

std::string read_small_file(const char* path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

bool parse_u64(std::string_view text, uint64_t& out) {
    const auto result = std::from_chars(text.data(), text.data() + text.size(), out);
    return result.ec == std::errc{} && result.ptr == text.data() + text.size();
}

double count_open_fds() {
    DIR* dir = opendir("/proc/self/fd");
    if (!dir) return 0;
    double count = 0;
    while (const dirent* entry = readdir(dir))
        if (entry->d_name[0] != '.') ++count;
    closedir(dir);
    return count - 1;  // the descriptor opendir itself holds
}

}  // namespace

bool parse_proc_self_stat(std::string_view text, proc_stat_fields& out) {
    // Field 2 is the command name in parentheses and may itself hold spaces and ')': the
    // fields we want are counted from the last ')'.
    const size_t close = text.rfind(')');
    if (close == std::string_view::npos) return false;
    std::string_view rest = text.substr(close + 1);
    int field = 2;
    while (!rest.empty()) {
        const size_t start = rest.find_first_not_of(' ');
        if (start == std::string_view::npos) break;
        rest = rest.substr(start);
        const size_t end = std::min(rest.find(' '), rest.size());
        const std::string_view token = rest.substr(0, end);
        rest = rest.substr(end);
        ++field;
        if (field == 14 && !parse_u64(token, out.utime_ticks)) return false;
        if (field == 15 && !parse_u64(token, out.stime_ticks)) return false;
        if (field == 22) return parse_u64(token, out.start_ticks);
    }
    return false;
}

uint64_t parse_boot_time(std::string_view text) {
    const size_t at = text.find("\nbtime ");
    if (at == std::string_view::npos) return 0;
    std::string_view rest = text.substr(at + 7);
    rest = rest.substr(0, std::min(rest.find('\n'), rest.size()));
    uint64_t seconds = 0;
    return parse_u64(rest, seconds) ? seconds : 0;
}

process_stats read_process_stats() {
    process_stats s;
    const long page = sysconf(_SC_PAGESIZE);
    const long ticks_per_second = sysconf(_SC_CLK_TCK);
    proc_stat_fields fields;
    if (page <= 0 || ticks_per_second <= 0 || !parse_proc_self_stat(read_small_file("/proc/self/stat"), fields))
        return s;

    std::istringstream statm(read_small_file("/proc/self/statm"));
    uint64_t size_pages = 0, resident_pages = 0;
    statm >> size_pages >> resident_pages;
    const auto tps = static_cast<double>(ticks_per_second);
    s.virtual_memory_bytes = static_cast<double>(size_pages) * static_cast<double>(page);
    s.resident_memory_bytes = static_cast<double>(resident_pages) * static_cast<double>(page);
    s.cpu_seconds = static_cast<double>(fields.utime_ticks + fields.stime_ticks) / tps;
    s.start_time_seconds = static_cast<double>(parse_boot_time(read_small_file("/proc/stat"))) +
                           static_cast<double>(fields.start_ticks) / tps;
    s.open_fds = count_open_fds();
    rlimit limit{};
    if (getrlimit(RLIMIT_NOFILE, &limit) == 0) s.max_fds = static_cast<double>(limit.rlim_cur);
    s.available = true;
    return s;
}

}  // namespace arena::ops
