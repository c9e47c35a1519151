#include "server/match/logger.hpp"

#include <algorithm>
#include <cstdarg>
#include <cstdio>

namespace arena::match {

void logger::operator()(const char* format, ...) const {
    if (!sink_) return;  // nothing formatted for nobody
    char line[1024];
    va_list args;
    va_start(args, format);
    const int n = std::vsnprintf(line, sizeof line, format, args);
    va_end(args);
    if (n < 0) return;
    sink_(std::string_view(line, std::min<size_t>(static_cast<size_t>(n), sizeof line - 1)));
}

}  // namespace arena::match
