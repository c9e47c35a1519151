// Which file a URL path names under the web root (server/net/static_files.*): no socket.
#include "server/net/static_files.hpp"

#include <unistd.h>
#include <catch2/catch.hpp>
#include <fstream>

using namespace arena::net;
namespace fs = std::filesystem;

TEST_CASE("static files resolve under the root only", "[net][http]") {
    const fs::path root = fs::temp_directory_path() / ("arena-static-" + std::to_string(::getpid()));
    fs::create_directories(root / "js");
    std::ofstream(root / "index.html") << "i";
    std::ofstream(root / "js" / "sdk.js") << "s";
    std::ofstream(root / "js" / "index.html") << "j";
    const static_files files(root);
    REQUIRE(files.serving());
    CHECK(files.resolve("/")->path == fs::canonical(root / "index.html"));
    CHECK(files.resolve("/js/")->path == fs::canonical(root / "js" / "index.html"));
    CHECK(files.resolve("/js/sdk.js")->content_type == "text/javascript; charset=utf-8");
    CHECK(files.resolve("//js//sdk.js"));
    CHECK(files.resolve("/js/%73dk.js"));  // %73 = 's'
    for (const char* bad : {"/../etc/passwd", "/js/../../etc/passwd", "/%2e%2e/etc/passwd", "/js/%2E%2E/%2E%2E/x",
                            "/.git/config", "/js\\..\\x", "/%00", "/%zz", "/%4", "relative", "/missing"}) {
        INFO(bad);
        static_refusal why;
        CHECK_FALSE(files.resolve(bad, &why));
        CHECK(why.status >= 400);
    }
    CHECK_FALSE(static_files("").serving());
    CHECK_FALSE(static_files(root / "nonexistent").resolve("/"));
    fs::remove_all(root);
}

TEST_CASE("content types by extension", "[net][http]") {
    CHECK(content_type_of("a.html") == "text/html; charset=utf-8");
    CHECK(content_type_of("a.js") == "text/javascript; charset=utf-8");
    CHECK(content_type_of("a.wasm") == "application/wasm");
    CHECK(content_type_of("a.css") == "text/css; charset=utf-8");
    CHECK(content_type_of("a.js.map") == "application/json");
    CHECK(content_type_of("wasm") == "application/octet-stream");
    CHECK(content_type_of("a.bin") == "application/octet-stream");
}
