#include "server/ops/stats_line.hpp"

#include <cstdio>

namespace arena::ops {

void stats_line_sink::key(const match::figure& f) {
    line_ += ' ';
    line_ += f.log;
    line_ += '=';
}

void stats_line_sink::whole(const match::figure& f, uint64_t value) {
    if (f.log.empty()) return;
    key(f);
    line_ += std::to_string(value);
}

void stats_line_sink::gauge(const match::figure& f, double value) {
    if (f.log.empty()) return;
    key(f);
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", f.decimals, value);
    line_ += text;
}

}  // namespace arena::ops
