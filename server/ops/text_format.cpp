#include "server/ops/text_format.hpp"

#include <charconv>
#include <cmath>

namespace arena::ops {

std::string format_number(double value) {
    if (std::isnan(value)) return "NaN";
    if (std::isinf(value)) return value > 0 ? "+Inf" : "-Inf";
    // Shortest round trip in %g style, as Go's FormatFloat(v, 'g', -1) writes "le" labels:
    // 0.0005 rather than 5e-04, so bucket labels look the same as every other exporter's.
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general);
    return std::string(buffer, result.ptr);
}

std::string escape_label_value(std::string_view value) {
    std::string out;
    out.reserve(value.size());
    for (char c : value) {
        if (c == '\\')
            out += "\\\\";
        else if (c == '"')
            out += "\\\"";
        else if (c == '\n')
            out += "\\n";
        else
            out += c;
    }
    return out;
}

std::string escape_help(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        if (c == '\\')
            out += "\\\\";
        else if (c == '\n')
            out += "\\n";
        else
            out += c;
    }
    return out;
}

void text_writer::family(std::string_view name, std::string_view type, std::string_view help) {
    out_ += "# HELP ";
    out_ += name;
    out_ += ' ';
    out_ += escape_help(help);
    out_ += "\n# TYPE ";
    out_ += name;
    out_ += ' ';
    out_ += type;
    out_ += '\n';
}

void text_writer::write_name_and_labels(std::string_view name, const label_list& labels) {
    out_ += name;
    if (labels.empty()) return;
    out_ += '{';
    for (size_t i = 0; i < labels.size(); ++i) {
        if (i) out_ += ',';
        out_ += labels[i].first;
        out_ += "=\"";
        out_ += escape_label_value(labels[i].second);
        out_ += '"';
    }
    out_ += '}';
}

void text_writer::sample(std::string_view name, double value, const label_list& labels) {
    write_name_and_labels(name, labels);
    out_ += ' ';
    out_ += format_number(value);
    out_ += '\n';
}

void text_writer::sample(std::string_view name, uint64_t value, const label_list& labels) {
    // Integers exactly, even above 2^53 where a double would round them.
    write_name_and_labels(name, labels);
    out_ += ' ';
    out_ += std::to_string(value);
    out_ += '\n';
}

void text_writer::histogram_family(std::string_view name, std::string_view help, const histogram& h) {
    family(name, "histogram", help);
    histogram_samples(name, h, {});
}

void text_writer::histogram_samples(std::string_view name, const histogram& h, const label_list& labels) {
    const std::string base(name);
    uint64_t cumulative = 0;
    const auto& bounds = h.upper_bounds();
    const auto& counts = h.bucket_counts();
    auto with = [&labels](std::string key, std::string value) {
        label_list all = labels;
        all.emplace_back(std::move(key), std::move(value));
        return all;
    };
    for (size_t i = 0; i < bounds.size(); ++i) {
        cumulative += counts[i];
        sample(base + "_bucket", cumulative, with("le", format_number(bounds[i])));
    }
    sample(base + "_bucket", h.count(), with("le", "+Inf"));
    sample(base + "_sum", h.sum(), labels);
    sample(base + "_count", h.count(), labels);
}

}  // namespace arena::ops
