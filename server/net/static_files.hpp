#pragma once
// Which file under the web root a URL path names, and its content type: the part of the
// HTTP port's static file serving that needs no socket, so that path traversal is tested
// without one. Only regular files under the root (after every symlink is resolved) are served;
// anything else is a 404, never a peek outside.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace arena::net {

struct static_file {
    std::filesystem::path path;  // canonical, under the root
    std::string content_type;
};

// What a refused path gets: the status and a one-line reason for the log.
struct static_refusal {
    int status = 404;
    std::string reason;
    bool hostile = false;  // a path no page links to (traversal, NUL, ...): worth a log line
};

class static_files {
public:
    // root: the folder served at "/". Empty or missing: nothing is served (every path a 404).
    explicit static_files(const std::filesystem::path& root);

    // The file a request path names ("/", "/app.js", "/sub/%20x.css"; the query already cut
    // off): "/" and a folder mean its index.html. Refused: percent escapes that do not decode,
    // NUL, backslashes, ".." and hidden (dot) segments, anything that resolves outside the root,
    // and anything that is not a regular file.
    [[nodiscard]] std::optional<static_file> resolve(std::string_view url_path, static_refusal* why = nullptr) const;

    [[nodiscard]] bool serving() const { return !root_.empty(); }
    [[nodiscard]] const std::filesystem::path& root() const { return root_; }

private:
    std::filesystem::path root_;  // canonical; empty when nothing is served
};

// The Content-Type for a file name, by its extension (.html, .js, .mjs, .wasm, .css, .map,
// .json, .svg, .png, .ico, .txt); application/octet-stream otherwise.
[[nodiscard]] std::string content_type_of(std::string_view file_name);

// The default web root for a program at `program` (argv[0] resolved): the built web folder
// beside its bin/ (`<prefix>/web`), else the installed one (`<prefix>/share/arena/web`), else
// empty.
[[nodiscard]] std::filesystem::path default_web_root(const std::filesystem::path& program);

}  // namespace arena::net
