// arena-token: mints a signed join token for arena-server --token-secret, or prints the
// server's current UDP connect key (--udp-connect-key) for clients that join over UDP.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <variant>

#include "protocol/player_name.hpp"
#include "server/auth/join_token.hpp"
#include "server/cli/bounds.hpp"
#include "server/cli_helpers.hpp"

namespace {

// A year: tokens travel in clear (SECURITY.md) and should live minutes to hours. The bound
// also keeps now + ttl far from int64's end, where it wrapped into an expired token.
constexpr arena::cli::number_bound ttl_bound{0, 365 * 86400, true, "s"};

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"arena-token: mint a signed join token", "arena-token"};
    std::string secret_path, name, match;
    int64_t ttl = 3600;
    bool connect_key = false;
    app.add_option("--secret", secret_path, "the server's secret file (at least 32 bytes)")->required();
    auto* name_option = app.add_option(
        "--name", name,
        "the player the token names: at most 64 bytes of UTF-8 without control characters, as the server "
        "requires (required unless --udp-connect-key)");
    auto* ttl_option = app.add_option("--ttl", ttl, "seconds until the token expires (default 3600)")
                           ->check(arena::cli::bounded(ttl_bound));
    auto* match_option =
        app.add_option("--match", match,
                       "the one match the token is good for (its id: 1 to 64 of A-Z, a-z, 0-9, '_' and '-'); "
                       "without it, any match of the server");
    app.add_flag("--udp-connect-key", connect_key,
                 "print, instead of a token, the server's current UDP connect key: a decimal number a UDP client "
                 "puts in ENet's connect data (enet_host_connect's last argument); the server accepts it for 5 "
                 "to 10 minutes")
        ->excludes(name_option)
        ->excludes(ttl_option)
        ->excludes(match_option);
    if (int code = arena::cli::parse_or_exit_code(app, argc, argv); code >= 0) return code;
    if (!connect_key && name_option->count() == 0) {
        std::fprintf(stderr, "arena-token: --name is required (see --help)\n");
        return 2;
    }
    // A token for a name the server refuses would only fail later, at the player's Hello.
    if (auto problem = connect_key ? std::nullopt : arena::protocol::player_name_problem(name)) {
        std::fprintf(stderr, "arena-token: --name: %s\n", problem->c_str());
        return 2;
    }
    const bool match_id_ok = std::all_of(match.begin(), match.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
    });
    if (match.size() > 64 || !match_id_ok) {
        std::fprintf(stderr, "arena-token: --match: 1 to 64 of A-Z, a-z, 0-9, '_' and '-'\n");
        return 2;
    }
    auto secret = arena::auth::token_secret::load(secret_path);
    if (!secret) {
        std::fprintf(stderr, "arena-token: %s\n", secret.error.c_str());
        return 2;
    }
    const auto& signer = secret.value;
    if (connect_key) {
        std::printf("%u\n", signer.connect_key(arena::auth::unix_now()));
        return 0;
    }
    std::printf("%s\n", signer.mint(name, arena::auth::unix_now() + ttl, match).c_str());
    return 0;
}
