#pragma once
// Small pieces every Arena program's command line shares.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <string>

#include "server/world/types.hpp"

namespace arena::cli {

// Parses "X,Y" into a vector of two finite numbers; false when malformed.
inline bool parse_vec2(const std::string& text, world::vec2& out) {
    const auto comma = text.find(',');
    if (comma == std::string::npos) return false;
    try {
        size_t used_x = 0, used_y = 0;
        const std::string xs = text.substr(0, comma), ys = text.substr(comma + 1);
        const float x = std::stof(xs, &used_x);
        const float y = std::stof(ys, &used_y);
        if (used_x != xs.size() || used_y != ys.size() || !std::isfinite(x) || !std::isfinite(y)) return false;
        out = {x, y};
        return true;
    } catch (const std::exception&) {
        return false;
    }
}

// A CLI11 option taking "X,Y".
inline CLI::Option* add_vec2_option(CLI::App& app, const std::string& name, world::vec2& target,
                                    const std::string& help) {
    return app
        .add_option_function<std::string>(
            name,
            [&target, name](const std::string& text) {
                if (!parse_vec2(text, target))
                    throw CLI::ValidationError(name, "expected X,Y (two finite numbers), got '" + text + "'");
            },
            help)
        ->type_name("X,Y");
}

// A finite number ≥ 0. CLI11's NonNegativeNumber lets "nan" through (every comparison with
// NaN is false), and a NaN radius or duration must never reach the server.
inline const CLI::Validator finite_non_negative(
    [](std::string& text) {
        double value = 0;
        if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value) || value < 0)
            return std::string("expected a finite number >= 0, got '") + text + "'";
        return std::string();
    },
    "NUMBER >= 0");

// Runs CLI11's parser; usage errors print one line and give exit code 2, --help gives 0.
// Returns -1 when parsing succeeded and the program should go on.
inline int parse_or_exit_code(CLI::App& app, int argc, char** argv) {
    try {
        app.parse(argc, argv);
        return -1;
    } catch (const CLI::CallForHelp&) {
        std::printf("%s", app.help().c_str());
        return 0;
    } catch (const CLI::CallForAllHelp&) {
        std::printf("%s", app.help("", CLI::AppFormatMode::All).c_str());
        return 0;
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "%s: %s (see --help)\n", app.get_name().c_str(), e.what());
        return 2;
    }
}

}  // namespace arena::cli
