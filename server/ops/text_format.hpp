#pragma once
// A writer of the Prometheus text exposition format, version 0.0.4: HELP and TYPE lines, then
// the samples of one family. It escapes what the format asks to be escaped and spells numbers
// the way Prometheus parses them (+Inf, NaN, shortest round-trip decimals).
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "server/ops/histogram.hpp"

namespace arena::ops {

using label_list = std::vector<std::pair<std::string, std::string>>;

class text_writer {
public:
    // Starts a family: "# HELP name help" and "# TYPE name type" (counter, gauge, histogram).
    void family(std::string_view name, std::string_view type, std::string_view help);
    void sample(std::string_view name, double value, const label_list& labels = {});
    void sample(std::string_view name, uint64_t value, const label_list& labels = {});
    // A whole histogram family: cumulative _bucket{le=...} lines, then _sum and _count.
    void histogram_family(std::string_view name, std::string_view help, const histogram& h);
    // One labelled histogram's lines, in a family already opened with family(name, "histogram", ...).
    void histogram_samples(std::string_view name, const histogram& h, const label_list& labels);

    const std::string& text() const { return out_; }

private:
    void write_name_and_labels(std::string_view name, const label_list& labels);
    std::string out_;
};

// Numbers as Prometheus reads them: "+Inf", "-Inf", "NaN", else the shortest exact decimal.
std::string format_number(double value);
// Label values escape backslash, double quote and newline.
std::string escape_label_value(std::string_view value);
// HELP text escapes backslash and newline.
std::string escape_help(std::string_view text);

}  // namespace arena::ops
