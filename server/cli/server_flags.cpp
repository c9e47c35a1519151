#include "server/cli/server_flags.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <variant>

#include "games/registry.hpp"
#include "server/cli/server_bounds.hpp"
#include "server/cli_helpers.hpp"
#include "server/config/config_json.hpp"
#include "server/config/modes.hpp"
#include "server/config/world_choice.hpp"
#include "server/net/static_files.hpp"
#include "server/ops/ops_flags.hpp"
#include "server/world/presets.hpp"

namespace arena::cli {

namespace {

// The world the match plays in: --config's file, else --preset's; --rules over either's rules.
// False: refused, said on stderr.
// The world and the game, from --preset, --config and --rules (server/config/world_choice.hpp).
bool choose_world(const std::string& preset, const std::string& config_file, const std::string& rules_name,
                  server_setup& out) {
    auto chosen = config::choose_world(preset, config_file, rules_name);
    if (!chosen) {
        std::fprintf(stderr, "arena-server: %s\n", chosen.error.c_str());
        return false;
    }
    out.world = chosen.value.config;
    out.host.match.preset = chosen.value.preset;
    return true;
}

// The modes (built in, then --modes FILE's) and the default match's: --mode's, else the
// one --preset names, else "custom", the world of --config or --rules. False: refused.
bool choose_modes(const std::string& modes_file, const std::string& mode_name, bool world_flags, server_setup& out) {
    host::host_options& options = out.host;
    options.modes = config::builtin_modes();
    if (!modes_file.empty()) {
        auto loaded = config::load_modes_file(modes_file);
        if (!loaded) {
            std::fprintf(stderr, "arena-server: --modes: %s\n", loaded.error.c_str());
            return false;
        }
        options.modes = config::merge_modes(std::move(options.modes), loaded.value);
    }
    if (!mode_name.empty()) {
        const config::mode* chosen = config::find_mode(options.modes, mode_name);
        if (!chosen) {
            std::fprintf(stderr, "arena-server: --mode: unknown mode '%s' (%s)\n", mode_name.c_str(),
                         config::mode_names(options.modes).c_str());
            return false;
        }
        options.default_mode = mode_name;
        options.match.preset = chosen->preset;
        out.world = chosen->world;
        return true;
    }
    // The preset's own mode, when --preset alone chose the world and a mode plays it as is.
    const bool plain_preset =
        !world_flags && (options.match.preset == "asteroids" || options.match.preset == "platformer");
    options.default_mode = options.match.preset == "platformer" ? "sandbox" : options.match.preset;
    if (!plain_preset) {
        options.default_mode = "custom";
        config::mode custom{"custom", out.world, options.match.preset, 0, 0};
        options.modes = config::merge_modes(std::move(options.modes), {custom});
    } else {
        out.world = config::find_mode(options.modes, options.default_mode)->world;
    }
    return true;
}

}  // namespace

bool record_is_folder(const std::string& record) {
    return !record.empty() && (record.back() == '/' || std::filesystem::is_directory(record));
}

int parse_server_flags(int argc, char** argv, server_setup& out) {
    CLI::App app{"arena-server: the authoritative Arena game server", "arena-server"};
    host::host_options& options = out.host;
    std::string preset = "asteroids", config_file, modes_file, mode_name;
    double handshake_s = 5, stall_s = 5, idle_s = 5;
    app.add_option("--bind", options.bind, "address to listen on (default 127.0.0.1; 0.0.0.0 for all)");
    app.add_option("--port", out.tcp.port, "TCP port (default 7777; 0 picks a free one)");
    int udp_port = -1;  // off
    app.add_option("--udp-port", udp_port,
                   "also accept clients over UDP (ENet) on this port (default: off; 0 picks a free one)")
        ->check(CLI::Range(0, 65535));
    int http_port = -1;  // off
    app.add_option("--http-port", http_port,
                   "also serve HTTP on this port (default: off; 0 picks a free one): the game over WebSocket at "
                   "/ws, /healthz, /metrics (unless --metrics-port is set), the web page's files at / (the replay "
                   "page at /replay), and with --serve-recording the --record file at /recording once the match "
                   "is over")
        ->check(CLI::Range(0, 65535));
    net::web_options web;
    std::string web_root;
    app.add_option("--web-root", web_root,
                   "folder served at / on --http-port (default: the built or installed web folder, if any)")
        ->check(CLI::ExistingDirectory);
    app.add_option("--allowed-origin", web.allowed_origins,
                   "with --http-port: only pages from this origin (e.g. https://play.example.com) may open /ws; "
                   "repeatable; '*' for any page (default: the server's own page, and programs that send no "
                   "Origin)");
    std::string udp_snapshot_copies = "auto";
    app.add_option("--udp-snapshot-copies", udp_snapshot_copies,
                   "send each UDP snapshot this many times (1 to 3), a tick apart: a lost one is replaced by its "
                   "copy, for that many times the downstream bytes; or 'auto': per client, twice while the "
                   "loss measured from its snapshot acks is above about 1 % (for 30 s at a time, then measured "
                   "again), else once (default auto: a clean link costs no extra byte)")
        ->check(CLI::IsMember({"1", "2", "3", "auto"}));
    app.add_option("--tick-rate", options.match.tick_rate, "world steps per second (default 60)")
        ->check(CLI::Range(1, 1000));
    app.add_option("--snapshot-rate", options.match.snapshot_rate, "snapshots per second (default 20)")
        ->check(CLI::Range(1, 1000));
    app.add_option("--max-players", options.match.admission.max_players, "players at once (default 64)")
        ->check(CLI::Range(1, 100000));
    app.add_option("--max-spectators", options.match.admission.max_spectators,
                   "spectators at once, besides the players (default 16; 0: none)")
        ->check(CLI::Range(0, 100000));
    app.add_option("--preset", preset,
                   "world preset: asteroids (default; plays the asteroids rules) or platformer (a sandbox)");
    app.add_option("--config", config_file, "world config file (JSON); overrides --preset");
    std::string rules_name;
    app.add_option(
        "--rules", rules_name,
        "game rules the match plays by: " + games::described_list() +
            "; overrides the preset's or the config file's (default: the preset's; a config's \"rules\", else "
            "sandbox)");
    app.add_option("--modes", modes_file,
                   "modes file (JSON): adds modes to the built-in ones (" + games::names_list() +
                       "), or overrides them by name (docs/MATCHES.md)");
    auto* mode_flag = app.add_option("--mode", mode_name,
                                     "the default match's mode (" + games::names_list() +
                                         ", or one of --modes); excludes "
                                         "--preset, --config and --rules");
    app.add_option("--max-matches", options.max_matches,
                   "matches at once in this process, the default one included (default: 50 per core, "
                   "each match's memory being small; 1 hosts the default match alone)")
        ->check(CLI::Range(1u, 100'000u));
    app.add_option("--threads", options.threads,
                   "threads that tick the matches, each match on one at a time (default: the machine's cores); "
                   "the transports and the HTTP port stay on one")
        ->check(CLI::Range(1u, 256u));
    app.add_option("--empty-match-seconds", options.empty_match_seconds,
                   "a match created on demand ends after this long without a client (default 30)")
        ->check(cli::finite_non_negative);
    app.add_option("--seed", options.match.seed, "world seed (default 1)");
    app.add_option("--record", out.record,
                   "record the session to FILE for arena-replay; a folder (existing, or ending in '/') records "
                   "every match, each to FOLDER/ID.arpl");
    app.add_option("--duration", options.duration_s,
                   "run this many seconds, then shut down cleanly (default: until a signal)")
        ->check(cli::finite_non_negative);
    app.add_option("--score-limit", options.match.score_limit,
                   "end the match when a player's score reaches N (default 0: no limit; rules that keep score)")
        ->check(CLI::Range(0u, 4000000000u));
    app.add_option("--stats-json", options.stats_json, "write the run's figures to FILE at exit");
    app.add_option("--input-buffer", options.match.input_buffer, "inputs buffered per player (default 8)")
        ->check(CLI::Range(1, 1024));
    app.add_option("--max-inputs-per-second", options.match.admission.max_inputs_per_second,
                   "inputs per second before a client is dropped (default 2 x tick rate + 10)");
    app.add_option("--handshake-timeout", handshake_s, "seconds a new connection has to send Hello (default 5)")
        ->check(CLI::PositiveNumber & cli::finite_non_negative);
    app.add_option("--idle-timeout", idle_s,
                   "seconds a joined client may go without sending an Input before it is dropped (default 5; 0: never)")
        ->check(cli::finite_non_negative);
    app.add_option("--stall-timeout", stall_s, "seconds a client may block our writes before it is dropped (default 5)")
        ->check(CLI::PositiveNumber & cli::finite_non_negative);
    app.add_option("--socket-send-buffer", options.socket_send_buffer,
                   "kernel send buffer per client, bytes (default 262144)")
        ->check(CLI::Range(4096, 64 << 20));
    app.add_option("--max-connections", options.match.admission.max_connections,
                   "open connections at once (default 2 x max players + max spectators + 16)");
    app.add_option("--max-pending-handshakes", options.match.admission.max_pending_handshakes,
                   "connections that have not sent Hello yet; when all are taken a new one takes the slot of the "
                   "oldest from the busiest address (default 0: max players + 16, at least 64)");
    app.add_option("--stats-interval", options.stats_interval_s, "seconds between stats log lines (default 5)")
        ->check(CLI::PositiveNumber & cli::finite_non_negative);
    app.add_option("--hash-interval", out.hash_interval,
                   "with --record: store the world hash every N ticks (default 60)")
        ->check(CLI::Range(1u, 1000000u));
    std::string token_secret_path;
    app.add_option("--token-secret", token_secret_path,
                   "admit only Hellos with a token signed with this secret file (see arena-token)");
    app.add_option("--reconnect-grace", options.match.reconnect_grace_s,
                   "seconds a dropped player's body waits for it to come back with the same token (default 10)")
        ->check(cli::finite_non_negative);
    // Interest management is on by default: 100 m is a quarter of the asteroids world's side,
    // a generous screen. 0 sends every body to every client.
    options.match.view_radius = 100;
    app.add_option("--view-radius", options.match.view_radius,
                   "m: each client's snapshots hold its body and the bodies this near it; 0 = the whole world")
        ->check(cli::finite_non_negative)
        ->capture_default_str();
    app.add_option("--lag-compensation-ms", options.match.lag_compensation_ms,
                   "judge each shot against the world as its shooter saw it, up to this far back (at most 64 ticks; "
                   "0: off, every shot against the present)")
        ->check(CLI::Range(0u, 10000u))
        ->capture_default_str();
    app.add_option("--delta-history", options.match.delta_history,
                   "snapshots kept per client as delta baselines; older acks get a full view")
        ->check(CLI::Range(1u, 1024u))
        ->capture_default_str();
    ops::ops_options& ops_options = out.ops;
    ops::add_ops_flags(app, ops_options);  // --metrics-port, --metrics-bind, --agones, --agones-port, ...
    double drain_grace_s = 1;
    app.add_option("--drain-grace", drain_grace_s, "seconds clients get to read their Bye at shutdown (default 1)")
        ->check(cli::finite_non_negative);
    cli::bound_server_flags(app);  // upper bounds: no seconds overflow into the past
    app.footer(
        "Signals: SIGINT, SIGTERM, SIGHUP and SIGUSR1 end the match in order (Bye to every client, the recording "
        "finished, --stats-json written, exit 0); SIGPIPE is ignored.");
    if (int code = cli::parse_or_exit_code(app, argc, argv); code >= 0) return code;
    // The Welcome tells clients the snapshot rate: it must be the one they get, a whole number
    // of ticks apart (asking for 50 at 60 Hz used to give 60, and 7 gave 7.5).
    if (options.match.tick_rate % options.match.snapshot_rate != 0) {
        std::fprintf(stderr, "arena-server: --snapshot-rate: %u does not divide the tick rate %u\n",
                     options.match.snapshot_rate, options.match.tick_rate);
        return 2;
    }
    if (auto error = ops::apply_agones_environment(ops_options, std::getenv("AGONES_SDK_HTTP_PORT")); !error.empty()) {
        std::fprintf(stderr, "arena-server: %s\n", error.c_str());
        return 2;
    }
    ops_options.bind = options.bind;
    // /recording serves the default match's.
    ops_options.recording =
        record_is_folder(out.record) ? (std::filesystem::path(out.record) / "default.arpl").string() : out.record;
    options.close_grace_ns = static_cast<int64_t>(drain_grace_s * 1e9);
    if (!token_secret_path.empty()) {
        auto secret = auth::token_secret::load(token_secret_path);
        if (!secret) {
            std::fprintf(stderr, "arena-server: --token-secret: %s\n", secret.error.c_str());
            return 2;
        }
        options.token_secret = std::move(secret.value);
    }
    options.match.admission.handshake_timeout = std::chrono::nanoseconds(static_cast<int64_t>(handshake_s * 1e9));
    options.stall_timeout_ns = static_cast<int64_t>(stall_s * 1e9);
    options.match.admission.idle_timeout = std::chrono::nanoseconds(static_cast<int64_t>(idle_s * 1e9));

    const bool world_flags = app.count("--preset") + app.count("--config") + app.count("--rules") > 0;
    if (mode_flag->count() > 0 && world_flags) {
        std::fprintf(stderr,
                     "arena-server: --mode: a mode names its own world and rules; leave out --preset, "
                     "--config and --rules (or add a mode with --modes)\n");
        return 2;
    }
    if (!choose_world(preset, config_file, rules_name, out)) return 2;
    if (app.count("--threads") == 0) options.threads = std::max(1u, std::thread::hardware_concurrency());
    if (app.count("--max-matches") == 0) options.max_matches = 50 * std::max(1u, std::thread::hardware_concurrency());
    if (!choose_modes(modes_file, mode_name, app.count("--config") + app.count("--rules") > 0, out)) return 2;

    if (udp_port >= 0)
        // 0: auto, a second copy per client while its measured loss calls for one.
        out.udp = net::udp_options{.port = static_cast<uint16_t>(udp_port),
                                   .snapshot_copies = udp_snapshot_copies == "auto"
                                                          ? 0u
                                                          : static_cast<uint32_t>(std::stoul(udp_snapshot_copies))};
    if (http_port >= 0) {
        web.port = static_cast<uint16_t>(http_port);
        web.web_root = web_root.empty() ? net::default_web_root("/proc/self/exe") : std::filesystem::path(web_root);
        web.recording = ops_options.recording;
        web.serve_recording = ops_options.serve_recording;
        web.serve_metrics = !ops_options.metrics_port;  // else /metrics only at --metrics-bind
        out.web = std::move(web);
    }
    return -1;
}

}  // namespace arena::cli
