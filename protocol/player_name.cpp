#include "protocol/player_name.hpp"

#include <cstdint>
#include <cstdio>

namespace arena::protocol {
namespace {

std::string problem_at(const char* what, std::string_view name, std::size_t at) {
    char text[96];
    std::snprintf(text, sizeof text, "name %s at byte %zu (0x%02x)", what, at, static_cast<std::uint8_t>(name[at]));
    return text;
}

// The length of the well-formed UTF-8 sequence starting at name[at] and its code point, or 0
// when the bytes there are not one (RFC 3629: shortest form, no surrogates, at most U+10FFFF).
// A few lines rather than a library: none of the project's Debian dependencies exposes a
// UTF-8 check that the protocol library (also built with clang++ for the fuzzers) could use.
std::size_t utf8_sequence(std::string_view name, std::size_t at, std::uint32_t& code_point) {
    const auto lead = static_cast<std::uint8_t>(name[at]);
    std::size_t length = 0;
    std::uint32_t min = 0;
    if (lead < 0x80) {
        code_point = lead;
        return 1;
    } else if (lead >= 0xc2 && lead <= 0xdf) {
        length = 2, min = 0x80, code_point = lead & 0x1fu;
    } else if (lead >= 0xe0 && lead <= 0xef) {
        length = 3, min = 0x800, code_point = lead & 0x0fu;
    } else if (lead >= 0xf0 && lead <= 0xf4) {
        length = 4, min = 0x10000, code_point = lead & 0x07u;
    } else {
        return 0;  // a continuation byte, an overlong two-byte lead (c0, c1) or f5..ff
    }
    if (name.size() - at < length) return 0;
    for (std::size_t k = 1; k < length; ++k) {
        const auto next = static_cast<std::uint8_t>(name[at + k]);
        if ((next & 0xc0u) != 0x80u) return 0;
        code_point = (code_point << 6) | (next & 0x3fu);
    }
    if (code_point < min || code_point > 0x10ffff || (code_point >= 0xd800 && code_point <= 0xdfff)) return 0;
    return length;
}

}  // namespace

std::optional<std::string> player_name_problem(std::string_view name, std::size_t max_bytes) {
    if (name.size() > max_bytes) return "name longer than " + std::to_string(max_bytes) + " bytes";
    for (std::size_t at = 0; at < name.size();) {
        std::uint32_t code_point = 0;
        const std::size_t length = utf8_sequence(name, at, code_point);
        if (length == 0) return problem_at("is not valid UTF-8", name, at);
        if (code_point < 0x20 || (code_point >= 0x7f && code_point <= 0x9f))
            return problem_at("has a control character", name, at);
        at += length;
    }
    return std::nullopt;
}

std::string printable_text(std::string_view text, std::size_t max_bytes) {
    const bool cut = text.size() > max_bytes;
    if (cut) text = text.substr(0, max_bytes);
    std::string out;
    out.reserve(text.size());
    for (std::size_t at = 0; at < text.size();) {
        std::uint32_t code_point = 0;
        const std::size_t length = utf8_sequence(text, at, code_point);
        if (length == 0 || code_point < 0x20 || (code_point >= 0x7f && code_point <= 0x9f)) {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\x%02x", static_cast<std::uint8_t>(text[at]));
            out += escaped;
            ++at;  // byte by byte: the rest of a broken sequence is judged on its own
            continue;
        }
        out.append(text.substr(at, length));
        at += length;
    }
    if (cut) out += "...";
    return out;
}

}  // namespace arena::protocol
