#include "server/host/log.hpp"

#include <chrono>

namespace arena::host {

namespace {
const auto process_start = std::chrono::steady_clock::now();
}  // namespace

match::logger server_logger() {
    return match::logger([](std::string_view line) { log_line("%.*s", static_cast<int>(line.size()), line.data()); });
}

void log_line(const char* format, ...) {
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - process_start).count();
    char line[1024];
    va_list args;
    va_start(args, format);
    std::vsnprintf(line, sizeof line, format, args);
    va_end(args);
    std::fprintf(stderr, "[%9.3f] %s\n", t, line);
}

}  // namespace arena::host
