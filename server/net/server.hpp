#pragma once
// The authoritative server: accepts TCP clients, runs the match at a fixed tick on one
// io_context thread, fans snapshots out, and shuts down cleanly on a signal or at the end of
// --duration.
#include <array>
#include <boost/asio.hpp>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "server/auth/join_token.hpp"
#include "server/host/intake.hpp"
#include "server/match/match.hpp"
#include "server/net/duration_histogram.hpp"
#include "server/net/tick_clock.hpp"
#include "server/net/udp_refusal_log.hpp"
#include "server/ops/accept_backoff.hpp"
#include "server/ops/histogram.hpp"
#include "server/ops/metrics.hpp"
#include "server/ops/process_counters.hpp"

namespace arena::net {

class session;

struct server_options {
    std::string bind = "127.0.0.1";
    uint16_t port = 7777;  // 0: any free port
    match::match_config match{};
    double duration_s = 0;                         // 0: run until a signal
    std::string stats_json;                        // written at exit when set
    uint32_t max_connections = 0;                  // 0: 2 × max_players + max_spectators + 16
    uint32_t max_pending_handshakes = 0;           // not sent Hello yet; 0: max_players + 16, at least 64
    int64_t handshake_timeout_ns = 5'000'000'000;  // Hello must arrive within this
    int64_t idle_timeout_ns = 5'000'000'000;       // a joined client's Inputs must not pause longer; 0: never
    int64_t stall_timeout_ns = 5'000'000'000;      // output stuck this long drops the client
    uint32_t max_control_frames = 64;              // queued control messages per client
    // Kernel send buffer per client, bytes: bounds the memory a client that does not read can
    // hold in the kernel (Linux would otherwise grow it to 4 MiB each) and lets a stall show.
    int socket_send_buffer = 256 * 1024;
    int64_t close_grace_ns = 1'000'000'000;          // a closing client may flush this long
    uint32_t max_catch_up = 5;                       // ticks run at once after a stall; more are overruns
    double stats_interval_s = 5;                     // period of the stats log line
    std::optional<auth::token_secret> token_secret;  // set: only signed, unexpired tokens join
};

// Traffic in the current stats window (the whole run's is in process_counters).
struct traffic {
    uint64_t bytes_in = 0;
    uint64_t bytes_out = 0;
};

class server {
public:
    server(boost::asio::io_context& io, const server_options& options, const world::world_config& world_config);

    // Binds, listens, prints "listening on HOST:PORT", and starts accepting and ticking.
    void start();
    // Stops accepting, says Bye to every client, and stops the io_context once they are gone
    // (or after the grace period). Idempotent.
    void shutdown(const std::string& reason);
    // Called once, after the last tick, before the io_context stops (recording, stats).
    std::function<void()> on_shutdown;

    // From sessions. The session's socket is closed: it is forgotten.
    void on_gone(session& s);
    void count_in(size_t bytes);
    // From a datagram transport (UDP): a client connection opened or closed there, counted
    // with the TCP sessions in connections_open and the peak; a snapshot sent as fragments.
    void count_peer_opened();
    void count_peer_closed();
    void count_fragmented_snapshot() { ++process_.snapshots_fragmented; }
    void count_snapshot_copy() { ++process_.snapshot_copies; }
    void count_udp_refusal(udp_refusal why) { ++process_.udp_refused[std::string(udp_refusal_key(why))]; }
    // From the other transports (WebSocket): a connection handed to the match opened, or is
    // gone. Counted with the TCP sessions (connections_open, the peak), and shutdown waits for it.
    void transport_opened();
    void transport_closed();
    // Client connections of every transport now.
    uint64_t open_connections() const { return open_sessions_ + peers_open_ + other_open_; }
    // The figures /metrics shows.
    ops::server_metrics metrics_snapshot() const;
    // The process's counters now.
    ops::process_counters process_counters() const;
    // True while the tick loop ran a tick within `window_ns`: /healthz and the Agones pings.
    bool ticking(int64_t window_ns = 1'000'000'000) const { return now_ns() - last_tick_ns_ < window_ns; }
    void count_out(size_t bytes);
    void count_out(size_t bytes, size_t messages);
    // A session has output to write: flushed after the handler running now (one post for all
    // the sessions a tick or a read gave output), so a tick's sends do not lengthen the tick.
    void request_flush(std::shared_ptr<session> s);
    uint32_t current_tick() const { return match_.state().tick(); }
    const server_options& options() const { return options_; }
    int64_t now_ns() const;
    bool shutting_down() const { return stopping_; }

    match::match& match() { return match_; }
    host::intake& intake() { return intake_; }
    uint16_t port() const { return port_; }
    void write_stats_json(const std::string& path) const;

private:
    boost::asio::awaitable<void> accept_loop();
    void warn_about_descriptor_limit() const;
    boost::asio::awaitable<void> tick_loop();
    void run_due_ticks();
    void read_sessions();   // what every client sent since the last tick
    void flush_sessions();  // writes what request_flush() asked for
    void check_stalled_sessions(int64_t now);
    void log_stats(int64_t now);
    void finish();

    boost::asio::io_context& io_;
    server_options options_;
    match::match match_;
    ops::process_counters process_;  // whole run (connections_open and tick_overruns filled when read)
    host::match_registry matches_{match_};
    host::intake intake_{matches_, process_};
    boost::asio::ip::tcp::acceptor acceptor_;
    ops::accept_backoff accept_backoff_;  // out of descriptors: pause accepting, log at a bounded rate
    uint16_t port_ = 0;
    // In accept order. A session closed while read_sessions() runs leaves a null behind (its
    // reference moves to gone_ until the loop ends), removed after the loop.
    std::vector<std::shared_ptr<session>> sessions_;
    std::vector<std::shared_ptr<session>> gone_;
    bool reading_sessions_ = false;
    size_t open_sessions_ = 0;
    uint64_t peers_open_ = 0;  // connections of datagram transports
    uint64_t other_open_ = 0;  // connections of other stream transports (WebSocket): shutdown waits for them
    std::vector<std::shared_ptr<session>> to_flush_;  // request_flush()'s, for the next flush_sessions()
    std::vector<std::shared_ptr<session>> flushing_;  // flush_sessions()' copy: flushing may ask again
    bool flush_posted_ = false;
    std::array<uint8_t, 64 * 1024> read_buffer_{};  // one for every session: one thread reads
    uint64_t next_session_id_ = 1;
    tick_clock clock_;
    boost::asio::steady_timer tick_timer_;
    boost::asio::steady_timer stop_timer_;
    bool stopping_ = false;
    bool finished_ = false;
    int64_t started_ns_ = 0;
    duration_histogram run_ticks_;
    duration_histogram window_ticks_;
    traffic window_traffic_;
    int64_t window_start_ns_ = 0;
    int64_t last_watchdog_ns_ = 0;
    ops::histogram tick_seconds_;
    int64_t last_tick_ns_ = 0;
};

}  // namespace arena::net
