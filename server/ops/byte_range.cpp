#include "server/ops/byte_range.hpp"

#include <charconv>
#include <optional>

namespace arena::ops {

namespace {

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
}

// Digits only (no sign, no space), at most 19 of them: anything else is not a number here.
std::optional<uint64_t> number(std::string_view s) {
    if (s.empty() || s.size() > 19) return std::nullopt;
    uint64_t v = 0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (r.ec != std::errc{} || r.ptr != s.data() + s.size()) return std::nullopt;
    return v;
}

}  // namespace

byte_range parse_byte_range(std::string_view header, uint64_t size) {
    const byte_range whole{byte_range::kind::whole, 0, size};
    header = trim(header);
    constexpr std::string_view unit = "bytes=";
    if (header.size() < unit.size() || header.substr(0, unit.size()) != unit) return whole;
    const std::string_view spec = trim(header.substr(unit.size()));
    if (spec.find(',') != std::string_view::npos) return whole;  // several ranges: not honoured
    const size_t dash = spec.find('-');
    if (dash == std::string_view::npos) return whole;
    const std::string_view from = trim(spec.substr(0, dash)), to = trim(spec.substr(dash + 1));
    if (from.empty()) {
        // "-N": the last N bytes.
        const auto n = number(to);
        if (!n) return whole;
        if (*n == 0 || size == 0) return {byte_range::kind::unsatisfiable, 0, 0};
        const uint64_t length = std::min(*n, size);
        return {byte_range::kind::partial, size - length, length};
    }
    const auto first = number(from);
    if (!first) return whole;
    uint64_t last = size == 0 ? 0 : size - 1;
    if (!to.empty()) {
        const auto l = number(to);
        if (!l || *l < *first) return whole;  // syntactically invalid: ignored
        last = std::min(*l, last);
    }
    if (*first >= size) return {byte_range::kind::unsatisfiable, 0, 0};
    return {byte_range::kind::partial, *first, last - *first + 1};
}

}  // namespace arena::ops
