#pragma once
// arena-server's run: the host (server/host/host.hpp) with the transports the flags asked for,
// and --record's recorder on the match's ticks.
#include "server/cli/server_flags.hpp"

namespace arena {

// Runs the server until its match is over; the exit code (2: --record cannot be opened).
// Throws what cannot bind.
int run_server(const cli::server_setup& setup);

}  // namespace arena
