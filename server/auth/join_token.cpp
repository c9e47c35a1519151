#include "server/auth/join_token.hpp"

#include <sodium.h>

#include <chrono>
#include <fstream>
#include <sstream>

#include "server/auth/key_window.hpp"

namespace arena::auth {

namespace {

constexpr size_t min_secret_bytes = 32;
constexpr std::string_view version_tag = "v1";
constexpr std::string_view match_version_tag = "v2";  // v1 and the match the token is good for

std::string to_base64url(std::string_view bytes) {
    const int variant = sodium_base64_VARIANT_URLSAFE_NO_PADDING;
    std::string out(sodium_base64_ENCODED_LEN(bytes.size(), variant), '\0');
    sodium_bin2base64(out.data(), out.size(), reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(),
                      variant);
    out.resize(std::char_traits<char>::length(out.c_str()));
    return out;
}

std::optional<std::string> from_base64url(std::string_view text) {
    std::string out(text.size(), '\0');
    size_t length = 0;
    if (sodium_base642bin(reinterpret_cast<unsigned char*>(out.data()), out.size(), text.data(), text.size(), nullptr,
                          &length, nullptr, sodium_base64_VARIANT_URLSAFE_NO_PADDING) != 0)
        return std::nullopt;
    out.resize(length);
    return out;
}

}  // namespace

result<token_secret> token_secret::from_bytes(std::string bytes) {
    using made = result<token_secret>;
    if (sodium_init() < 0) return made::failure("libsodium failed to initialise");
    if (bytes.size() < min_secret_bytes)
        return made::failure("the secret has " + std::to_string(bytes.size()) + " bytes; at least " +
                             std::to_string(min_secret_bytes) + " are needed");
    return made::success(token_secret(std::move(bytes)));
}

result<token_secret> token_secret::load(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return result<token_secret>::failure(path + ": cannot open the token secret");
    std::ostringstream bytes;
    bytes << in.rdbuf();
    auto secret = from_bytes(bytes.str());
    if (!secret) secret.error = path + ": " + secret.error;
    return secret;
}

std::string token_secret::mac(std::string_view message) const {
    unsigned char out[crypto_auth_hmacsha256_BYTES];
    crypto_auth_hmacsha256_state state;
    crypto_auth_hmacsha256_init(&state, reinterpret_cast<const unsigned char*>(key_.data()), key_.size());
    crypto_auth_hmacsha256_update(&state, reinterpret_cast<const unsigned char*>(message.data()), message.size());
    crypto_auth_hmacsha256_final(&state, out);
    return std::string(reinterpret_cast<const char*>(out), sizeof out);
}

std::string token_secret::mint(std::string_view name, int64_t expires, std::string_view match) const {
    std::string body(match.empty() ? version_tag : match_version_tag);
    body.append(".").append(to_base64url(name)).append(".").append(std::to_string(expires));
    if (!match.empty()) body.append(".").append(to_base64url(match));
    return body + "." + to_base64url(mac(body));
}

result<token_claims> token_secret::verify(std::string_view token, int64_t now) const {
    using refused = result<token_claims>;
    const size_t last_dot = token.rfind('.');
    if (last_dot == std::string_view::npos) return refused::failure("malformed token");
    const std::string_view body = token.substr(0, last_dot);
    const auto given_mac = from_base64url(token.substr(last_dot + 1));
    const std::string expected = mac(body);
    // Constant-time comparison: a mismatch position must not leak through timing.
    if (!given_mac || given_mac->size() != expected.size() ||
        sodium_memcmp(given_mac->data(), expected.data(), expected.size()) != 0)
        return refused::failure("token signature does not match this server's secret");
    // The signature is ours, so the body has the shape we wrote: v1.NAME.EXPIRES, or
    // v2.NAME.EXPIRES.MATCH.
    const size_t first = body.find('.'), second = body.find('.', first + 1);
    const std::string_view tag = body.substr(0, first);
    if ((tag != version_tag && tag != match_version_tag) || second == std::string_view::npos)
        return refused::failure("malformed token");
    const size_t third = tag == match_version_tag ? body.find('.', second + 1) : body.size();
    if (third == std::string_view::npos) return refused::failure("malformed token");
    const auto name = from_base64url(body.substr(first + 1, second - first - 1));
    if (!name) return refused::failure("malformed token");
    token_claims claims{*name, 0, {}};
    if (tag == match_version_tag) {
        const auto match = from_base64url(body.substr(third + 1));
        if (!match || match->empty()) return refused::failure("malformed token");
        claims.match = *match;
    }
    try {
        claims.expires = std::stoll(std::string(body.substr(second + 1, third - second - 1)));
    } catch (const std::exception&) {
        return refused::failure("malformed token");
    }
    if (claims.expires <= now)
        return refused::failure("token expired at " + std::to_string(claims.expires) + " (now " + std::to_string(now) +
                                ")");
    return refused::success(std::move(claims));
}

std::uint32_t token_secret::connect_key(int64_t unix_seconds) const {
    const int64_t window = key_window(unix_seconds, connect_key_window_s);
    // Domain separation: every token body starts with "v1." and this message does not, so a
    // key is never part of a token's MAC, nor this MAC a token's.
    const std::string digest = mac("udp-connect.v1." + std::to_string(window));
    const auto byte = [&](size_t i) {
        return static_cast<std::uint32_t>(static_cast<unsigned char>(digest[i]));
    };
    return byte(0) << 24 | byte(1) << 16 | byte(2) << 8 | byte(3);
}

int64_t unix_now() {
    return std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch())
        .count();
}

}  // namespace arena::auth
