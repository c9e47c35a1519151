#pragma once
// Bounds for numeric flags. A number a program converts (seconds to int64 nanoseconds, to
// ticks in a uint32, to a float) must be refused before the conversion can overflow: a
// stall timeout of 1e10 s wrapped to a negative duration and dropped every client. Each
// bound is a usage error (exit 2) naming the flag; none saturates.
//
// Only CLI11 here (no world types), so that any library with flags can use it.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <string>

namespace arena::cli {

// A closed or half-open interval of finite numbers, with the unit for messages and help.
struct number_bound {
    double min = 0;
    double max = 0;
    bool min_exclusive = false;  // (min, max] rather than [min, max]
    const char* unit = "";       // "s", "m", ... (may be empty)
};

// "(0, 3600] s" or "[0, 60] s": the interval as help and errors say it.
inline std::string describe(const number_bound& b) {
    char text[96];
    std::snprintf(text, sizeof text, "%c%.10g, %.10g]%s%s", b.min_exclusive ? '(' : '[', b.min, b.max,
                  *b.unit ? " " : "", b.unit);
    return text;
}

// True when `text` is one finite number inside `b` (NaN and infinities are outside any).
inline bool within(const std::string& text, const number_bound& b) {
    double value = 0;
    if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value)) return false;
    return (b.min_exclusive ? value > b.min : value >= b.min) && value <= b.max;
}

// A CLI11 validator for `b`. CLI11 prefixes its message with the flag's name, so a refusal
// reads "--stall-timeout: expected a number in (0, 3600] s, got '1e10'".
inline CLI::Validator bounded(const number_bound& b) {
    return CLI::Validator(
        [b](std::string& text) {
            if (within(text, b)) return std::string();
            return "expected a number in " + describe(b) + ", got '" + text + "'";
        },
        "NUMBER in " + describe(b));
}

// Adds `b` to the option `name` of `app`, declared before; --help shows the interval. A
// missing option is a programming error: get_option throws CLI::OptionNotFound at start-up.
inline void bound_option(CLI::App& app, const std::string& name, const number_bound& b) {
    app.get_option(name)->check(bounded(b));
}

}  // namespace arena::cli
