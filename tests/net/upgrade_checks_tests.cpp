// The checks of a WebSocket upgrade that need no socket (server/net/upgrade_checks.*).
#include <catch2/catch.hpp>

#include "server/net/upgrade_checks.hpp"

using arena::net::origin_allowed;
using arena::net::valid_websocket_key;

TEST_CASE("Sec-WebSocket-Key must be the base64 of 16 bytes", "[net][http]") {
    CHECK(valid_websocket_key("dGhlIHNhbXBsZSBub25jZQ=="));  // RFC 6455's example
    CHECK_FALSE(valid_websocket_key("!!!!"));
    CHECK_FALSE(valid_websocket_key(""));
    CHECK_FALSE(valid_websocket_key("dGhlIHNhbXBsZSBub25jZQ"));        // no padding
    CHECK_FALSE(valid_websocket_key("dGhlIHNhbXBsZSBub25jZQ=x"));      // bad padding
    CHECK_FALSE(valid_websocket_key("dGhlIHNhbXBsZSBub25j!Q=="));      // not base64
    CHECK_FALSE(valid_websocket_key("dGhlIHNhbXBsZSBub25jZQ==AAAA"));  // longer than 16 bytes
}

TEST_CASE("by default /ws admits the page's own origin or none, --allowed-origin lists others, '*' any",
          "[net][http]") {
    const std::vector<std::string> by_default;
    CHECK(origin_allowed(by_default, "", "127.0.0.1:8080"));  // a program, not a browser
    CHECK(origin_allowed(by_default, "http://127.0.0.1:8080", "127.0.0.1:8080"));
    CHECK(origin_allowed(by_default, "https://Play.Example.com", "play.example.com"));
    CHECK_FALSE(origin_allowed(by_default, "https://evil.example.net", "play.example.com"));
    CHECK_FALSE(origin_allowed(by_default, "http://127.0.0.1:9090", "127.0.0.1:8080"));  // another port
    CHECK_FALSE(origin_allowed(by_default, "null", "127.0.0.1:8080"));
    CHECK_FALSE(origin_allowed(by_default, "http://x", ""));
    const std::vector<std::string> listed{"https://play.example.com"};
    CHECK(origin_allowed(listed, "https://PLAY.example.com", "anything"));
    CHECK_FALSE(origin_allowed(listed, "", "play.example.com"));  // as before: a list wants an Origin
    CHECK_FALSE(origin_allowed(listed, "https://play.example.com.evil.net", "x"));
    const std::vector<std::string> any{"*"};
    CHECK(origin_allowed(any, "https://evil.example.net", "x"));
    CHECK(origin_allowed(any, "", "x"));
}
