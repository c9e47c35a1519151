#pragma once
// A run's figures, each described once and reported to any sink: the --stats-json writer, the
// /metrics writer, the periodic stats log line, a test. A counters struct has one report() that
// lists its figures, so that adding a figure is one line there and it shows up everywhere.
#include <cstdint>
#include <map>
#include <string>
#include <string_view>

namespace arena::match {

// What one figure is called where it appears. Empty: it does not appear there.
struct figure {
    std::string_view stats;   // --stats-json field ("joins"; "snapshots/delta_frames" nests)
    std::string_view metric;  // /metrics family ("arena_player_joins_total")
    std::string_view help;    // one line for the metric's HELP, with its unit
    std::string_view log{};   // key in the stats log line ("players"), in the order reported
    int decimals = 3;         // digits after the point of a fractional gauge in the log line
};

class figure_sink {
public:
    virtual ~figure_sink() = default;
    // Only grows over a run (a Prometheus counter).
    virtual void counter(const figure& f, uint64_t value) = 0;
    // Goes up and down (a Prometheus gauge); whole numbers stay whole in JSON.
    virtual void gauge(const figure& f, uint64_t value) = 0;
    virtual void gauge(const figure& f, double value) = 0;
    // One counter per label value (a labelled counter; an object in JSON without its zeros).
    virtual void counters_by(const figure& f, std::string_view label,
                             const std::map<std::string, uint64_t>& values) = 0;
};

}  // namespace arena::match
