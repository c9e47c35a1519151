#pragma once
// The checks of a WebSocket upgrade request that need no socket (web_transport.cpp), so that
// they are tested on strings: the key's form and whose page the request comes from.
#include <string>
#include <string_view>
#include <vector>

namespace arena::net {

// Sec-WebSocket-Key must be the base64 of 16 bytes (RFC 6455 §4.1): 22 characters of the
// base64 alphabet and "==".
[[nodiscard]] bool valid_websocket_key(std::string_view key);

// Whether a page of `origin` (the Origin header, "" when absent) may open /ws on a request for
// `host` (the Host header). allowed empty: the page's own origin (Origin's host[:port] equal
// to Host, without regard to case) or no Origin at all (a program, not a browser, which sends
// none); otherwise only the origins listed (compared without regard to case), "*" any.
[[nodiscard]] bool origin_allowed(const std::vector<std::string>& allowed, std::string_view origin,
                                  std::string_view host);

}  // namespace arena::net
