#pragma once
// One line per event on stderr, prefixed with seconds since the process started, so that
// operators and tests can read joins, leaves, rejects and the periodic figures.
#include <cstdarg>
#include <cstdio>

namespace arena::net {

#if defined(__GNUC__)
__attribute__((format(printf, 1, 2)))
#endif
void log_line(const char* format, ...);

// Turns log lines off (fuzz targets, which would otherwise print millions).
void set_logging(bool enabled);

}  // namespace arena::net
