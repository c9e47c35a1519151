#include <catch2/catch.hpp>
#include <variant>

#include "server/auth/join_token.hpp"

using namespace arena::auth;

namespace {

token_secret secret(const std::string& bytes) {
    return token_secret::from_bytes(bytes).value;
}

const std::string key_a(32, 'a');
const std::string key_b(32, 'b');

}  // namespace

TEST_CASE("a minted token verifies and names its player", "[auth]") {
    const auto s = secret(key_a);
    const std::string token = s.mint("ada.lovelace", 2000);
    auto claims = s.verify(token, 1000);
    REQUIRE(claims.ok());
    CHECK(claims.value.name == "ada.lovelace");
    CHECK(claims.value.expires == 2000);
}

TEST_CASE("expired, forged and malformed tokens are refused with a reason", "[auth]") {
    const auto s = secret(key_a);
    const std::string token = s.mint("ada", 2000);
    auto expired = s.verify(token, 2000);
    REQUIRE(!expired.ok());
    CHECK(expired.error.find("expired") != std::string::npos);

    auto other_secret = secret(key_b).verify(token, 1000);
    REQUIRE(!other_secret.ok());
    CHECK(other_secret.error.find("signature") != std::string::npos);

    // Changing the name or the expiry breaks the signature.
    std::string renamed = token;
    renamed[3] = renamed[3] == 'Y' ? 'Z' : 'Y';
    CHECK(!s.verify(renamed, 1000).ok());
    const std::string extended = s.mint("ada", 2000).replace(token.find(".2000") + 1, 4, "9999");
    CHECK(!s.verify(extended, 1000).ok());

    for (const char* junk : {"", ".", "v1", "garbage.token", "v1.x.y.z", "...."}) CHECK(!s.verify(junk, 1000).ok());
}

TEST_CASE("a token minted for one match says which, and one minted for none says none", "[auth]") {
    const auto s = secret(key_a);
    const std::string bound = s.mint("ada", 2000, "finals-7");
    CHECK(bound.substr(0, 3) == "v2.");
    auto claims = s.verify(bound, 1000);
    REQUIRE(claims.ok());
    CHECK(claims.value.name == "ada");
    CHECK(claims.value.expires == 2000);
    CHECK(claims.value.match == "finals-7");
    CHECK(s.verify(s.mint("ada", 2000), 1000).value.match.empty());
    // The match is signed: a token moved to another match (or stripped of it) is refused.
    std::string moved = bound;
    const size_t last = moved.rfind('.'), before = moved.rfind('.', last - 1);
    moved.replace(before + 1, last - before - 1, "ZmluYWxzLTg");  // "finals-8"
    CHECK(!s.verify(moved, 1000).ok());
    std::string stripped = "v1" + bound.substr(2, before - 2) + bound.substr(last);
    CHECK(!s.verify(stripped, 1000).ok());
    CHECK(!s.verify(s.mint("ada", 1000, "finals-7"), 1000).ok());  // expired all the same
}

TEST_CASE("a secret shorter than 32 bytes is refused", "[auth]") {
    auto short_secret = token_secret::from_bytes("too short");
    REQUIRE(!short_secret.ok());
    CHECK(short_secret.error.find("32") != std::string::npos);
    CHECK(!token_secret::load("/nonexistent/secret").ok());
}

TEST_CASE("the UDP connect key is the HMAC of its 300 s window's message, the same all window long", "[auth][udp]") {
    const auto s = secret(key_a);
    // Reference values: the first 4 bytes, big endian, of HMAC-SHA-256 keyed with 32 'a' of
    // "udp-connect.v1.6000000" (and of ...5999999, and of ...-1), computed with Python's hmac.
    const int64_t window_start = 6'000'000LL * connect_key_window_s;
    CHECK(s.connect_key(window_start) == 3244867605u);
    CHECK(s.connect_key(window_start + connect_key_window_s - 1) == 3244867605u);
    CHECK(s.connect_key(window_start - 1) == 2062987443u);
    CHECK(s.connect_key(-1) == 1497567035u);  // windows are floored, also before the epoch
    CHECK(s.connect_key(window_start + connect_key_window_s) != s.connect_key(window_start));
    // Another secret, another key.
    CHECK(secret(key_b).connect_key(window_start) != s.connect_key(window_start));
}
