#pragma once
// One line per event on stderr, prefixed with seconds since the process started, so that
// operators and tests can read joins, leaves, rejects and the periodic figures.
#include <cstdarg>
#include <cstdio>

#include "server/match/logger.hpp"

namespace arena::host {

#if defined(__GNUC__)
__attribute__((format(printf, 1, 2)))
#endif
void log_line(const char* format, ...);

// A logger for the match that writes through log_line.
match::logger server_logger();

}  // namespace arena::host
