#pragma once
// Signed join tokens: "v1.<name>.<expires>.<mac>", where name is base64url, expires is a Unix
// time in seconds, and mac is HMAC-SHA-256 (libsodium) of "v1.<name>.<expires>" keyed with
// the server's secret file, base64url; or "v2.<name>.<expires>.<match>.<mac>", a token good
// for one match only (its id, base64url), the MAC over everything before it. The token names the player: a server with
// a secret admits only Hellos whose token it signed and that have not expired, and knows who they are. Tokens travel in
// clear over TCP (see SECURITY.md).
//
// The same secret derives the UDP connect key: ENet's CONNECT command carries 32 bits of user
// data, too few for a token, so a client puts there the first 4 bytes (big endian) of the HMAC
// of "udp-connect.v1.<window>", window = Unix seconds / 300. The UDP transport refuses a connect
// without the key of the current or the previous window before ENet gives it a peer slot.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "server/world/result.hpp"

namespace arena::auth {

// Seconds per UDP connect key window: a key is accepted for 5 to 10 minutes.
inline constexpr int64_t connect_key_window_s = 300;

struct token_claims {
    std::string name;     // the player the token was minted for
    int64_t expires = 0;  // Unix seconds
    std::string match;    // the match it is good for; "": any
};

class token_secret {
public:
    // Reads the secret from a file: at least 32 bytes (e.g. `head -c 32 /dev/urandom > FILE`).
    static result<token_secret> load(const std::string& path);
    // For tests and tools: a secret from bytes already in memory (at least 32 bytes).
    static result<token_secret> from_bytes(std::string bytes);

    // `match` "": a token good for any match (v1); else for that match alone (v2).
    std::string mint(std::string_view name, int64_t expires, std::string_view match = {}) const;
    // The claims of a valid, unexpired token, or why it is refused.
    result<token_claims> verify(std::string_view token, int64_t now) const;
    // The UDP connect key of the window holding `unix_seconds` (see above).
    std::uint32_t connect_key(int64_t unix_seconds) const;

private:
    // Only load() and from_bytes() make a usable secret; the empty one exists for result's
    // value slot, and a failed result's value is never used.
    friend struct arena::result<token_secret>;
    token_secret() = default;
    explicit token_secret(std::string key) : key_(std::move(key)) {}
    std::string mac(std::string_view message) const;
    std::string key_;
};

// Seconds since the Unix epoch, for expiry checks (outside the world: a wall clock is fine).
int64_t unix_now();

}  // namespace arena::auth
