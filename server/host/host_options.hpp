#pragma once
// The host's configuration: the match, the run, and the rules every client connection keeps
// whatever its transport (timeouts, output limits). Each transport's own port and options are
// its own (tcp_transport.hpp, udp_transport.hpp, web_transport.hpp).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "server/auth/join_token.hpp"
#include "server/config/modes.hpp"
#include "server/match/match.hpp"

namespace arena::host {

struct host_options {
    std::string bind = "127.0.0.1";  // the address every transport listens on
    match::match_config match{};     // every match's, its mode's capacity over max_players
    // What the matches play: every mode a Hello or the lobby may name, and the default match's.
    std::vector<config::mode> modes = config::builtin_modes();
    std::string default_mode = "asteroids";
    uint32_t max_matches = 1;                  // matches at once, the default one included
    double empty_match_seconds = 30;           // a match created on demand ends after this long empty
    unsigned threads = 1;                      // threads that tick the matches, the io thread included
    double duration_s = 0;                     // 0: run until a signal
    std::string stats_json;                    // written at exit when set
    int64_t stall_timeout_ns = 5'000'000'000;  // output stuck this long drops the client
    uint32_t max_control_frames = 64;          // queued control messages per client
    // Kernel send buffer per client, bytes: bounds the memory a client that does not read can
    // hold in the kernel (Linux would otherwise grow it to 4 MiB each) and lets a stall show.
    int socket_send_buffer = 256 * 1024;
    int64_t close_grace_ns = 1'000'000'000;          // a closing client may flush this long
    uint32_t max_catch_up = 5;                       // ticks run at once after a stall; more are overruns
    double stats_interval_s = 5;                     // period of the stats log line
    std::optional<auth::token_secret> token_secret;  // set: only signed, unexpired tokens join
};

}  // namespace arena::host
