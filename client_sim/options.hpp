#pragma once
// arena-bots' command line.
#include <cstdint>
#include <optional>
#include <string>

#include "client_sim/behavior.hpp"
#include "client_sim/misbehave.hpp"
#include "server/auth/join_token.hpp"

namespace arena::bots {

enum class transport_kind : std::uint8_t { tcp, udp, ws };

struct options {
    std::string host = "127.0.0.1";
    std::uint16_t port = 7777;
    std::uint32_t bots = 10;
    double duration = 10;  // s, from the first connection attempt to the Byes
    behavior_choice behavior = behavior_choice::mixed;
    std::uint64_t seed = 1;
    double connect_rate = 200;  // new connections per second; 0 = all at once
    std::string json;           // summary as JSON to this file; empty = none
    misbehavior misbehave = misbehavior::none;
    double misbehave_share = 0.1;  // [0, 1], of the bots, when misbehave != none
    std::string name_prefix = "bot";
    std::string token;  // Hello.token of every bot (an open server's reconnection key)
    // --token-secret FILE: each bot mints its own signed token naming it (load tests of a
    // server that runs with the same secret).
    std::optional<auth::token_secret> token_secret;
    bool quiet = false;                              // no progress lines
    double join_timeout = 10;                        // s from launch to Welcome before a bot gives up
    bool full_snapshots = false;                     // do not ask for delta snapshots (the simple client's path)
    std::string match;                               // Hello.match: every bot joins this match
    std::string mode;                                // Hello.mode: every bot joins or creates a match of this mode
    transport_kind transport = transport_kind::tcp;  // udp: ENet, to a server's --udp-port; ws: its --http-port /ws
    double simulate_latency_ms = 0;                  // udp: added each way on the bot's side
    double simulate_jitter_ms = 0;                   // udp: ± uniform around it
};

// Parses argv into `out`. Returns -1 when the program should go on, else its exit code
// (0 after --help, 2 on a usage error, with the message already printed).
int parse_options(int argc, char** argv, options& out);

// The token bot `name` says Hello with: minted from the secret when there is one.
std::string token_for(const options& opts, const std::string& name);

}  // namespace arena::bots
