#pragma once
// The window a Unix time falls in, for keys that change every `window_s` seconds: the join
// token's UDP connect key (join_token.hpp) and the connect gate that checks it
// (server/net/udp_connect_gate.hpp). Header-only and free of the token code, so that the
// gate (and its fuzz target) need not link it.
#include <cstdint>

namespace arena::auth {

// Floor division, so that the window just before the epoch is -1, not 0 a second time.
constexpr std::int64_t key_window(std::int64_t unix_seconds, std::int64_t window_s) {
    return unix_seconds / window_s - (unix_seconds % window_s < 0 ? 1 : 0);
}

static_assert(key_window(0, 300) == 0 && key_window(299, 300) == 0 && key_window(300, 300) == 1);
static_assert(key_window(-1, 300) == -1 && key_window(-300, 300) == -1 && key_window(-301, 300) == -2);

}  // namespace arena::auth
