// arena-server: the authoritative game server. Wiring only: the flags (cli/server_flags.hpp)
// and the run (server_run.hpp): a host with its transports (server/host/, server/net/).
#include <csignal>
#include <cstdio>
#include <exception>

#include "server/cli/server_flags.hpp"
#include "server/server_run.hpp"

int main(int argc, char** argv) {
    arena::cli::server_setup setup;
    if (const int code = arena::cli::parse_server_flags(argc, argv, setup); code >= 0) return code;
    std::signal(SIGPIPE, SIG_IGN);  // a log reader that went away (`| head`) must not kill the match
    try {
        return arena::run_server(setup);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "arena-server: %s\n", e.what());
        return 1;
    }
}
