// arena-token: mints a signed join token for arena-server --token-secret.
#include <cstdio>
#include <variant>

#include "server/auth/join_token.hpp"
#include "server/cli_helpers.hpp"

int main(int argc, char** argv) {
    CLI::App app{"arena-token: mint a signed join token", "arena-token"};
    std::string secret_path, name;
    int64_t ttl = 3600;
    app.add_option("--secret", secret_path, "the server's secret file (at least 32 bytes)")->required();
    app.add_option("--name", name, "the player the token names")->required();
    app.add_option("--ttl", ttl, "seconds until the token expires (default 3600)")->check(CLI::PositiveNumber);
    if (int code = arena::cli::parse_or_exit_code(app, argc, argv); code >= 0) return code;
    auto secret = arena::auth::token_secret::load(secret_path);
    if (auto* e = std::get_if<arena::auth::token_error>(&secret)) {
        std::fprintf(stderr, "arena-token: %s\n", e->reason.c_str());
        return 2;
    }
    std::printf("%s\n", std::get<arena::auth::token_secret>(secret).mint(name, arena::auth::unix_now() + ttl).c_str());
    return 0;
}
