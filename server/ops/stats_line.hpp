#pragma once
// The periodic stats log line's side of server/match/figures.hpp: each figure with a log name
// becomes "key=value", in the order the report()s list them, so that a figure named once in a
// report() appears in the line as it does in --stats-json and /metrics.
#include <string>

#include "server/match/figures.hpp"

namespace arena::ops {

class stats_line_sink : public match::figure_sink {
public:
    void counter(const match::figure& f, uint64_t value) override { whole(f, value); }
    void gauge(const match::figure& f, uint64_t value) override { whole(f, value); }
    void gauge(const match::figure& f, double value) override;
    // Labelled counters have no place on one line: they are in --stats-json and /metrics.
    void counters_by(const match::figure&, std::string_view, const std::map<std::string, uint64_t>&) override {}

    // "stats" and every field so far: "stats players=2 ticks=300 ...".
    const std::string& line() const { return line_; }

private:
    void whole(const match::figure& f, uint64_t value);
    void key(const match::figure& f);
    std::string line_ = "stats";
};

}  // namespace arena::ops
