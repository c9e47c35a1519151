// arena-token as an operator runs it: it mints only tokens the server can accept.
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <fstream>
#include <string>
#include <variant>

#include "common/run_command.hpp"
#include "server/auth/join_token.hpp"

using namespace arena::test;

namespace {

struct secret_file {
    std::string path = "/tmp/arena-token-test-" + std::to_string(::getpid()) + ".secret";
    secret_file() { std::ofstream(path) << std::string(32, 's'); }
    ~secret_file() { std::remove(path.c_str()); }
};

command_result token(const std::string& args) {
    return run_command(program("arena-token") + " " + args + " 2>&1");
}

}  // namespace

TEST_CASE("arena-token mints for a valid name and refuses names the server refuses", "[auth][cli]") {
    secret_file secret;
    const auto ok = token("--secret " + secret.path + " --name 'Zoë' --ttl 60");
    CHECK(ok.exit_code == 0);
    CHECK(ok.output.rfind("v1.", 0) == 0);

    const auto long_name = token("--secret " + secret.path + " --name " + std::string(65, 'x'));
    CHECK(long_name.exit_code == 2);
    CHECK(long_name.output == "arena-token: --name: name longer than 64 bytes\n");

    const auto newline = token("--secret " + secret.path + " --name \"$(printf 'eve\\nINFO forged')\"");
    CHECK(newline.exit_code == 2);
    CHECK(newline.output == "arena-token: --name: name has a control character at byte 3 (0x0a)\n");

    const auto not_utf8 = token("--secret " + secret.path + " --name \"$(printf 'bad\\377')\"");
    CHECK(not_utf8.exit_code == 2);
    CHECK(not_utf8.output == "arena-token: --name: name is not valid UTF-8 at byte 3 (0xff)\n");
}

TEST_CASE("arena-token refuses a --ttl that would wrap into an expired token", "[auth][cli]") {
    secret_file secret;
    for (const char* ttl : {"9223372036854775000", "31536001", "0", "-5", "nan"}) {
        INFO(ttl);
        const auto r = token("--secret " + secret.path + " --name ada --ttl " + ttl);
        CHECK(r.exit_code == 2);
        CHECK(r.output.find("--ttl") != std::string::npos);
        CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);  // one line
    }
    CHECK(token("--secret " + secret.path + " --name ada --ttl 31536000").exit_code == 0);
}

TEST_CASE("arena-token --udp-connect-key prints the server's current connect key, in decimal", "[auth][cli][udp]") {
    secret_file secret;
    const auto key = token("--secret " + secret.path + " --udp-connect-key");
    CHECK(key.exit_code == 0);
    REQUIRE(!key.output.empty());
    CHECK(key.output.back() == '\n');
    const std::string digits = key.output.substr(0, key.output.size() - 1);
    CHECK(!digits.empty());
    CHECK(std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }));
    // The key the server derives from the same secret now (or a moment ago, had the window
    // just turned).
    const auto server_secret = arena::auth::token_secret::load(secret.path).value;
    const int64_t now = arena::auth::unix_now();
    const std::uint64_t printed = std::stoull(digits);
    CHECK((printed == server_secret.connect_key(now) || printed == server_secret.connect_key(now - 5)));
    // It keys the server, it names nobody: no --name or --ttl beside it.
    CHECK(token("--secret " + secret.path + " --udp-connect-key --name ada").exit_code == 2);
    CHECK(token("--secret " + secret.path + " --udp-connect-key --ttl 60").exit_code == 2);
    // Without it, a token as ever, and --name is still required.
    CHECK(token("--secret " + secret.path + " --name ada").output.rfind("v1.", 0) == 0);
    const auto no_name = token("--secret " + secret.path);
    CHECK(no_name.exit_code == 2);
    CHECK(no_name.output == "arena-token: --name is required (see --help)\n");
}
