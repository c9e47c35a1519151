#include "server/net/static_files.hpp"

#include <array>
#include <system_error>

namespace arena::net {

namespace fs = std::filesystem;

namespace {

int hex_value(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

// %XX escapes decoded; nothing when one is malformed. '+' stays '+' (it means a space only in
// query strings).
std::optional<std::string> percent_decode(std::string_view in) {
    std::string out;
    out.reserve(in.size());
    for (size_t i = 0; i < in.size(); ++i) {
        if (in[i] != '%') {
            out.push_back(in[i]);
            continue;
        }
        if (i + 2 >= in.size()) return std::nullopt;
        const int hi = hex_value(in[i + 1]), lo = hex_value(in[i + 2]);
        if (hi < 0 || lo < 0) return std::nullopt;
        out.push_back(static_cast<char>(hi * 16 + lo));
        i += 2;
    }
    return out;
}

bool under(const fs::path& root, const fs::path& p) {
    auto r = root.begin(), q = p.begin();
    for (; r != root.end(); ++r, ++q)
        if (q == p.end() || *r != *q) return false;
    return true;
}

std::optional<static_file> refuse(static_refusal* why, int status, std::string reason, bool hostile = false) {
    if (why != nullptr) *why = {status, std::move(reason), hostile};
    return std::nullopt;
}

}  // namespace

static_files::static_files(const fs::path& root) {
    if (root.empty()) return;
    std::error_code ec;
    fs::path canonical = fs::canonical(root, ec);
    if (!ec && fs::is_directory(canonical, ec)) root_ = std::move(canonical);
}

std::optional<static_file> static_files::resolve(std::string_view url_path, static_refusal* why) const {
    if (root_.empty()) return refuse(why, 404, "no web root is served");
    if (url_path.empty() || url_path.front() != '/') return refuse(why, 400, "the path does not start with /");
    const std::optional<std::string> decoded = percent_decode(url_path);
    if (!decoded) return refuse(why, 400, "a malformed percent escape", true);
    fs::path relative;
    std::string_view rest = std::string_view(*decoded).substr(1);
    while (!rest.empty()) {
        const size_t slash = rest.find('/');
        const std::string_view segment = rest.substr(0, slash);
        rest = slash == std::string_view::npos ? std::string_view() : rest.substr(slash + 1);
        if (segment.empty()) continue;  // "//" and a trailing "/"
        if (segment.find('\0') != std::string_view::npos || segment.find('\\') != std::string_view::npos)
            return refuse(why, 400, "NUL or backslash in the path", true);
        // "..", "." and hidden files (.git, .env): never served.
        if (segment.front() == '.') return refuse(why, 404, "a dot segment in the path", true);
        relative /= fs::path(std::string(segment));
    }
    std::error_code ec;
    fs::path candidate = root_ / relative;
    if (fs::is_directory(candidate, ec)) candidate /= "index.html";
    fs::path canonical = fs::canonical(candidate, ec);
    if (ec) return refuse(why, 404, "no such file");
    // A symlink inside the root may point outside it: the resolved path decides.
    if (!under(root_, canonical)) return refuse(why, 404, "resolves outside the web root", true);
    if (!fs::is_regular_file(canonical, ec)) return refuse(why, 404, "not a regular file");
    std::string type = content_type_of(canonical.filename().string());
    return static_file{std::move(canonical), std::move(type)};
}

std::string content_type_of(std::string_view file_name) {
    struct mapping {
        std::string_view extension;
        std::string_view type;
    };
    static constexpr std::array<mapping, 11> types{{
        {".html", "text/html; charset=utf-8"},
        {".js", "text/javascript; charset=utf-8"},
        {".mjs", "text/javascript; charset=utf-8"},
        {".wasm", "application/wasm"},
        {".css", "text/css; charset=utf-8"},
        {".map", "application/json"},
        {".json", "application/json"},
        {".svg", "image/svg+xml"},
        {".png", "image/png"},
        {".ico", "image/x-icon"},
        {".txt", "text/plain; charset=utf-8"},
    }};
    for (const mapping& m : types)
        if (file_name.size() > m.extension.size() && file_name.ends_with(m.extension)) return std::string(m.type);
    return "application/octet-stream";
}

fs::path default_web_root(const fs::path& program) {
    std::error_code ec;
    const fs::path exe = fs::canonical(program, ec);
    if (ec) return {};
    const fs::path prefix = exe.parent_path().parent_path();  // <prefix>/bin/arena-server
    for (const fs::path& p : {prefix / "web", prefix / "share" / "arena" / "web"})
        if (fs::is_directory(p, ec)) return p;
    return {};
}

}  // namespace arena::net
