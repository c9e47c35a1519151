#include "server/net/upgrade_checks.hpp"

#include <algorithm>
#include <cctype>

namespace arena::net {

namespace {

bool is_base64(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '+' || c == '/';
}

bool iequals(std::string_view a, std::string_view b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
           });
}

}  // namespace

bool valid_websocket_key(std::string_view key) {
    if (key.size() != 24 || key.substr(22) != "==") return false;
    return std::all_of(key.begin(), key.begin() + 22, is_base64);
}

bool origin_allowed(const std::vector<std::string>& allowed, std::string_view origin, std::string_view host) {
    if (allowed.empty()) {
        if (origin.empty()) return true;
        // "scheme://host[:port]": the part after the scheme names the page's server.
        const size_t scheme_end = origin.find("://");
        if (scheme_end == std::string_view::npos) return false;  // "null" (a file, a sandbox) and the like
        return !host.empty() && iequals(origin.substr(scheme_end + 3), host);
    }
    for (const std::string& a : allowed)
        if (a == "*" || iequals(a, origin)) return true;
    return false;
}

}  // namespace arena::net
