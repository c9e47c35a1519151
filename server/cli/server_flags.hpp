#pragma once
// arena-server's flags: declared, parsed, checked and turned into the host's, the transports'
// and the recording's options. A bad value is refused here with a one-line error naming the
// flag (exit 2), before anything binds.
#include <cstdint>
#include <optional>
#include <string>

#include "server/host/host_options.hpp"
#include "server/net/tcp_transport.hpp"
#include "server/net/udp_transport.hpp"
#include "server/net/web_transport.hpp"
#include "server/ops/ops_service.hpp"
#include "server/world/config.hpp"

namespace arena::cli {

struct server_setup {
    host::host_options host;
    ops::ops_options ops;
    net::tcp_options tcp;
    std::optional<net::udp_options> udp;  // --udp-port
    std::optional<net::web_options> web;  // --http-port
    world::world_config world;
    std::string record;           // --record: the file or folder, or empty
    uint32_t hash_interval = 60;  // --hash-interval, ticks
};

// Whether --record names a folder (one recording per match): an existing directory, or a
// path ending in '/'.
bool record_is_folder(const std::string& record);

// -1: run with `out`; otherwise the exit code (0 after --help, 2 for a refused flag).
int parse_server_flags(int argc, char** argv, server_setup& out);

}  // namespace arena::cli
