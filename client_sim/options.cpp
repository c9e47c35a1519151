#include "client_sim/options.hpp"

#include <cstdio>
#include <variant>

#include <CLI/CLI.hpp>

#include "server/cli_helpers.hpp"

namespace arena::bots {

int parse_options(int argc, char** argv, options& out) {
    CLI::App app{"Simulated Arena players: N bots over N TCP connections, with client-side prediction", "arena-bots"};
    std::string behavior_name = "mixed";
    std::string misbehave_name = "none";
    app.add_option("--host", out.host, "server address")->capture_default_str();
    app.add_option("--port", out.port, "server TCP port")->check(CLI::Range(1, 65535))->capture_default_str();
    app.add_option("--bots", out.bots, "number of bots (connections)")
        ->check(CLI::Range(1u, 100000u))
        ->capture_default_str();
    app.add_option("--duration", out.duration, "seconds to run, then say Bye")
        ->check(CLI::Range(0.1, 86400.0))
        ->capture_default_str();
    app.add_option("--behavior", behavior_name,
                   "random|seek|orbit|idle|hunter|game|mixed (mixed: by bot index; game: the game's own bot, as "
                   "soccer's, else seek)")
        ->check(CLI::IsMember({"random", "seek", "orbit", "idle", "hunter", "game", "mixed"}))
        ->capture_default_str();
    app.add_option("--seed", out.seed, "seed of the behaviours (with the bot index)")->capture_default_str();
    app.add_option("--connect-rate", out.connect_rate, "new connections per second (0: all at once)")
        ->check(CLI::Range(0.0, 1e6))
        ->capture_default_str();
    app.add_option("--json", out.json, "also write the summary as JSON to this file");
    app.add_option("--misbehave", misbehave_name,
                   "fault for a share of the bots: garbage|oversize|nan|slow-reader|flood|abrupt-close")
        ->check(CLI::IsMember({"none", "garbage", "oversize", "nan", "slow-reader", "flood", "abrupt-close"}));
    app.add_option("--misbehave-share", out.misbehave_share, "share of the bots that misbehave, [0, 1]")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
    app.add_option("--name-prefix", out.name_prefix, "bots are named PREFIX-INDEX")->capture_default_str();
    app.add_option("--token", out.token, "Hello.token of every bot (a server with --token-secret wants one)");
    std::string token_secret_path;
    app.add_option("--token-secret", token_secret_path,
                   "mint each bot a signed token naming it from this secret file (as arena-token does); over UDP, "
                   "each bot also puts the server's connect key in ENet's connect data");
    app.add_option("--join-timeout", out.join_timeout, "seconds a bot waits for its Welcome")
        ->check(CLI::Range(0.1, 3600.0))
        ->capture_default_str();
    app.add_option("--match", out.match, "join the match with this id (the lobby's GET /matches lists them)");
    app.add_option("--mode", out.mode,
                   "join the fullest open match of this mode with a seat, or create one (join-or-create); with "
                   "neither, the server's default match");
    app.add_flag("--quiet,-q", out.quiet, "no progress line each second");
    app.add_flag("--full-snapshots", out.full_snapshots,
                 "ask for full BodyState snapshots instead of deltas (no Hello.delta_snapshots)");

    std::string transport_name = "tcp";
    app.add_option("--transport", transport_name,
                   "tcp, udp (ENet; --port is then the server's --udp-port) or ws (WebSocket to ws://HOST:PORT/ws; "
                   "--port is then the server's --http-port)")
        ->check(CLI::IsMember({"tcp", "udp", "ws"}))
        ->capture_default_str();
    app.add_option("--simulate-latency", out.simulate_latency_ms,
                   "ms added to every message each way on the bot's side (with --transport udp)")
        ->check(CLI::Range(0.0, 10000.0));
    app.add_option("--simulate-jitter", out.simulate_jitter_ms,
                   "ms: each message's added delay varies by up to this either way (with --transport udp)")
        ->check(CLI::Range(0.0, 10000.0));

    if (const int code = cli::parse_or_exit_code(app, argc, argv); code >= 0) return code;
    out.transport = transport_name == "udp"  ? transport_kind::udp
                    : transport_name == "ws" ? transport_kind::ws
                                             : transport_kind::tcp;
    if (out.transport != transport_kind::udp && (out.simulate_latency_ms > 0 || out.simulate_jitter_ms > 0)) {
        std::fprintf(
            stderr,
            "arena-bots: --simulate-latency and --simulate-jitter delay datagrams: they need --transport udp\n");
        return 2;
    }
    if (!token_secret_path.empty()) {
        auto secret = auth::token_secret::load(token_secret_path);
        if (!secret) {
            std::fprintf(stderr, "arena-bots: --token-secret: %s\n", secret.error.c_str());
            return 2;
        }
        out.token_secret = std::move(secret.value);
    }
    // IsMember has checked both names.
    out.behavior = *parse_behavior(behavior_name);
    out.misbehave = *parse_misbehavior(misbehave_name);
    return -1;
}

std::string token_for(const options& opts, const std::string& name) {
    // An hour is far longer than any load test, and short enough to be harmless if seen.
    if (opts.token_secret) return opts.token_secret->mint(name, auth::unix_now() + 3600);
    return opts.token;
}

}  // namespace arena::bots
