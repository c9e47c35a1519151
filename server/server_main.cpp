// arena-server: the authoritative game server. Wiring only: flags, the world config, the
// server, signals.
#include <boost/asio.hpp>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <variant>

#include "protocol/snapshot.hpp"
#include "server/cli/server_bounds.hpp"
#include "server/cli_helpers.hpp"
#include "server/config/config_json.hpp"
#include "server/config/world_choice.hpp"
#include "server/net/log.hpp"
#include "server/net/server.hpp"
#include "server/net/udp_transport.hpp"
#include "server/net/web_transport.hpp"
#include "server/ops/ops_flags.hpp"
#include "server/ops/ops_service.hpp"
#include "server/replay/recorder.hpp"
#include "server/world/presets.hpp"

using namespace arena;

int main(int argc, char** argv) {
    CLI::App app{"arena-server: the authoritative Arena game server", "arena-server"};
    net::server_options options;
    std::string preset = "asteroids", config_file, record;
    double handshake_s = 5, stall_s = 5, idle_s = 5;
    app.add_option("--bind", options.bind, "address to listen on (default 127.0.0.1; 0.0.0.0 for all)");
    app.add_option("--port", options.port, "TCP port (default 7777; 0 picks a free one)");
    int udp_port = -1;  // off
    app.add_option("--udp-port", udp_port,
                   "also accept clients over UDP (ENet) on this port (default: off; 0 picks a free one)")
        ->check(CLI::Range(0, 65535));
    int http_port = -1;  // off
    app.add_option("--http-port", http_port,
                   "also serve HTTP on this port (default: off; 0 picks a free one): the game over WebSocket at "
                   "/ws, /metrics, /healthz, the web page's files at / (the replay page at /replay), and "
                   "the --record file at /recording")
        ->check(CLI::Range(0, 65535));
    net::web_options web;
    std::string web_root;
    app.add_option("--web-root", web_root,
                   "folder served at / on --http-port (default: the built or installed web folder, if any)")
        ->check(CLI::ExistingDirectory);
    app.add_option("--allowed-origin", web.allowed_origins,
                   "with --http-port: only pages from this origin (e.g. https://play.example.com) may open /ws; "
                   "repeatable (default: any)");
    uint32_t udp_snapshot_copies = 1;
    app.add_option("--udp-snapshot-copies", udp_snapshot_copies,
                   "send each UDP snapshot this many times, a tick apart: a lost one is replaced by its copy, "
                   "for that many times the downstream bytes (default 1: no copy)")
        ->check(CLI::Range(1, 3));
    app.add_option("--tick-rate", options.match.tick_rate, "world steps per second (default 60)")
        ->check(CLI::Range(1, 1000));
    app.add_option("--snapshot-rate", options.match.snapshot_rate, "snapshots per second (default 20)")
        ->check(CLI::Range(1, 1000));
    app.add_option("--max-players", options.match.max_players, "players at once (default 64)")
        ->check(CLI::Range(1, 100000));
    app.add_option("--max-spectators", options.match.max_spectators,
                   "spectators at once, besides the players (default 16; 0: none)")
        ->check(CLI::Range(0, 100000));
    app.add_option("--preset", preset,
                   "world preset: asteroids (default; plays the asteroids rules) or platformer (a sandbox)");
    app.add_option("--config", config_file, "world config file (JSON); overrides --preset");
    std::string rules_name;
    app.add_option(
        "--rules", rules_name,
        "game rules the match plays by: sandbox (no score) or asteroids (bullets, lives, score); "
        "overrides the preset's or the config file's (default: the preset's; a config's \"rules\", else sandbox)");
    app.add_option("--seed", options.match.seed, "world seed (default 1)");
    app.add_option("--record", record, "record the session to FILE for arena-replay");
    app.add_option("--duration", options.duration_s,
                   "run this many seconds, then shut down cleanly (default: until a signal)")
        ->check(cli::finite_non_negative);
    app.add_option("--score-limit", options.match.score_limit,
                   "end the match when a player's score reaches N (default 0: no limit; rules that keep score)")
        ->check(CLI::Range(0u, 4000000000u));
    app.add_option("--stats-json", options.stats_json, "write the run's figures to FILE at exit");
    app.add_option("--input-buffer", options.match.input_buffer, "inputs buffered per player (default 8)")
        ->check(CLI::Range(1, 1024));
    app.add_option("--max-inputs-per-second", options.match.max_inputs_per_second,
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
    app.add_option("--max-connections", options.max_connections,
                   "open connections at once (default 2 x max players + max spectators + 16)");
    app.add_option("--max-pending-handshakes", options.max_pending_handshakes,
                   "connections that have not sent Hello yet; when all are taken a new one takes the slot of the "
                   "oldest from the busiest address (default 0: max players + 16, at least 64)");
    app.add_option("--stats-interval", options.stats_interval_s, "seconds between stats log lines (default 5)")
        ->check(CLI::PositiveNumber & cli::finite_non_negative);
    uint32_t hash_interval = 60;
    app.add_option("--hash-interval", hash_interval, "with --record: store the world hash every N ticks (default 60)")
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
    app.add_option("--delta-history", options.match.delta_history,
                   "snapshots kept per client as delta baselines; older acks get a full view")
        ->check(CLI::Range(1u, 1024u))
        ->capture_default_str();
    ops::ops_options ops_options;
    ops::add_ops_flags(app, ops_options);  // --metrics-port, --metrics-bind, --agones, --agones-port, ...
    double drain_grace_s = 1;
    app.add_option("--drain-grace", drain_grace_s, "seconds clients get to read their Bye at shutdown (default 1)")
        ->check(cli::finite_non_negative);
    cli::bound_server_flags(app);  // upper bounds: no seconds overflow into the past
    if (int code = cli::parse_or_exit_code(app, argc, argv); code >= 0) return code;
    // The Welcome tells clients the snapshot rate: it must be the one they get, a whole number
    // of ticks apart (asking for 50 at 60 Hz used to give 60, and 7 gave 7.5).
    if (options.match.tick_rate % options.match.snapshot_rate != 0) {
        std::fprintf(stderr, "arena-server: --snapshot-rate: %u does not divide the tick rate %u\n",
                     options.match.snapshot_rate, options.match.tick_rate);
        return 2;
    }
    std::signal(SIGPIPE, SIG_IGN);  // a log reader that went away (`| head`) must not kill the match
    if (auto error = ops::apply_agones_environment(ops_options, std::getenv("AGONES_SDK_HTTP_PORT")); !error.empty()) {
        std::fprintf(stderr, "arena-server: %s\n", error.c_str());
        return 2;
    }
    ops_options.bind = options.bind;
    options.close_grace_ns = static_cast<int64_t>(drain_grace_s * 1e9);
    if (!token_secret_path.empty()) {
        auto secret = auth::token_secret::load(token_secret_path);
        if (auto* e = std::get_if<auth::token_error>(&secret)) {
            std::fprintf(stderr, "arena-server: --token-secret: %s\n", e->reason.c_str());
            return 2;
        }
        options.token_secret = std::get<auth::token_secret>(std::move(secret));
    }
    options.handshake_timeout_ns = static_cast<int64_t>(handshake_s * 1e9);
    options.stall_timeout_ns = static_cast<int64_t>(stall_s * 1e9);
    options.idle_timeout_ns = static_cast<int64_t>(idle_s * 1e9);

    auto chosen = config::choose_world(preset, config_file, rules_name);  // server/config/world_choice.hpp
    if (auto* e = std::get_if<config::config_error>(&chosen)) {
        std::fprintf(stderr, "arena-server: %s\n", e->message.c_str());
        return 2;
    }
    const world::world_config world_config = std::get<config::world_choice>(chosen).config;
    options.match.preset = std::get<config::world_choice>(chosen).preset;

    try {
        boost::asio::io_context io(1);
        net::server server(io, options, world_config);
        // SIGHUP (the terminal closed) shuts down in order, like SIGTERM.
        boost::asio::signal_set signals(io, SIGINT, SIGTERM, SIGHUP);
        signals.async_wait([&](const boost::system::error_code& ec, int signo) {
            if (!ec)
                server.shutdown(signo == SIGINT   ? "server interrupted (SIGINT)"
                                : signo == SIGHUP ? "server hung up (SIGHUP)"
                                                  : "server terminated (SIGTERM)");
        });
        // --record: every tick goes to the file as the session runs; finished at shutdown.
        std::optional<replay::recorder> recorder;
        bool recording_failed = false;
        if (!record.empty()) {
            const world::world& w = server.match().state();
            auto opened =
                replay::recorder::open(record, replay::make_header(w, options.match.preset, options.match.seed,
                                                                   options.match.tick_rate, hash_interval));
            if (!opened) {
                std::fprintf(stderr, "arena-server: --record: %s\n", opened.error.c_str());
                return 2;
            }
            recorder.emplace(std::move(opened.value));
            server.match().on_tick = [&](const match::tick_record& r, uint64_t hash) {
                if (auto s = recorder->record_tick(r, hash); !s && !recording_failed) {
                    net::log_line("recording failed, the session goes on unrecorded: %s", s.error.c_str());
                    recording_failed = true;
                }
            };
            server.on_shutdown = [&] {
                if (recording_failed) return;
                // The state hash (the world's, then the rules'), as every recorded tick's.
                const uint64_t end_hash = rules::state_hash(w, server.match().game_rules());
                if (auto s = recorder->finish(w.tick(), end_hash); !s)
                    net::log_line("recording failed at the end: %s", s.error.c_str());
                else
                    net::log_line("recorded %u ticks to %s", w.tick(), record.c_str());
            };
        }
        ops::ops_service ops(
            io, ops_options, [&] { return server.metrics_snapshot(); }, [&] { return server.ticking(); },
            [](const std::string& line) { net::log_line("%s", line.c_str()); });
        server.start();
        std::optional<net::udp_transport> udp;
        if (udp_port >= 0) {
            udp.emplace(
                io, server,
                net::udp_options{.port = static_cast<uint16_t>(udp_port), .snapshot_copies = udp_snapshot_copies});
            udp->start();  // prints "udp listening on HOST:PORT" after the TCP line
        }
        std::optional<net::web_transport> http;
        if (http_port >= 0) {
            web.port = static_cast<uint16_t>(http_port);
            web.web_root = web_root.empty() ? net::default_web_root("/proc/self/exe") : std::filesystem::path(web_root);
            web.recording = record;
            http.emplace(io, server, web,
                         ops::http_handlers{[&ops] { return ops.metrics_text(); },
                                            [&server] {
                                                return server.ticking();
                                            }});
            http->start();  // prints "http listening on HOST:PORT"
        }
        ops.start_after_listening();  // binds --metrics-port, then POST /ready to Agones
        io.run();                     // until the server drained: Bye sent, recording and stats flushed
        io.restart();                 // the match is over: tell Agones (bounded), then exit 0
        ops.on_match_end([&io] { io.stop(); });
        io.run();
        net::log_line("stopped after %u ticks", server.current_tick());
        if (const uint64_t n = protocol::non_finite_values_replaced(); n > 0)  // protocol/snapshot.hpp
            net::log_line("error: the world diverged: %llu non-finite values were sent as 0 (check the world config)",
                          static_cast<unsigned long long>(n));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "arena-server: %s\n", e.what());
        return 1;
    }
    return 0;
}
