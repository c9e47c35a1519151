#pragma once
// The house the matches live in: one io_context run on the calling thread, the signals that
// end a run, the fixed-rate tick loop, the registry of matches (match_registry.hpp), the ops endpoint
// and the Agones client, the stats, and the orderly shutdown. Transports plug in through
// transport.hpp; the host knows none of them by name. A tick: every transport's
// read_before_tick() (what clients sent goes through the intake to its match), every match's
// ticks, every transport's flush_after_tick().
#include <boost/asio.hpp>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "server/host/duration_histogram.hpp"
#include "server/host/host_options.hpp"
#include "server/host/intake.hpp"
#include "server/host/match_registry.hpp"
#include "server/host/tick_clock.hpp"
#include "server/host/transport.hpp"
#include "server/match/match.hpp"
#include "server/ops/histogram.hpp"
#include "server/ops/metrics.hpp"
#include "server/ops/ops_service.hpp"
#include "server/ops/process_counters.hpp"

namespace arena::host {

class process_host final : public transport_host {
public:
    // The default match plays options.default_mode. Throws when it cannot start.
    process_host(const host_options& options, const ops::ops_options& ops);
    ~process_host();
    process_host(const process_host&) = delete;
    process_host& operator=(const process_host&) = delete;

    // A transport, started by start() in the order added (their "listening" lines in that order).
    void add(std::unique_ptr<transport> t);
    // Starts the transports, the tick loop, --duration's timer, the signals, then the ops
    // endpoint and Agones' Ready. Throws when something cannot bind.
    void start();
    // Runs the io_context on this thread until the run is over: drained (Bye sent, recording
    // and stats written), then Agones told (bounded).
    void run();
    // Stops the transports taking clients, says Bye to every client, and stops once they are
    // gone (or after the grace period). Idempotent.
    void shutdown(const std::string& reason);
    // Called once, after the last tick, before the io_context stops (recording, stats).
    std::function<void()> on_shutdown;

    match::match& default_match() { return matches_.default_match(); }
    const match::match& default_match() const { return matches_.default_match(); }
    uint32_t current_tick() const { return matches_.default_match().state().tick(); }
    // What /metrics and /healthz answer (for the HTTP port's routes).
    ops::http_handlers http_handlers();
    // The figures /metrics shows.
    ops::server_metrics metrics_snapshot() const;
    // The process's counters now.
    ops::process_counters process_counters() const;
    // True while the tick loop ran a tick within `window_ns`: /healthz and the Agones pings.
    bool ticking(int64_t window_ns = 1'000'000'000) const { return now_ns() - last_tick_ns_ < window_ns; }
    void write_stats_json(const std::string& path) const;

    // transport_host
    boost::asio::io_context& io() override { return io_; }
    const host_options& options() const override { return options_; }
    arena::host::intake& intake() override { return intake_; }
    match_registry& matches() override { return matches_; }
    lobby_answer lobby(const lobby_request& request) override;
    ops::process_counters& counters() override { return process_; }
    int64_t now_ns() const override;
    bool shutting_down() const override { return stopping_; }
    void connection_opened() override;
    void connection_closed() override;

private:
    void watch_signals();
    void warn_about_descriptor_limit() const;
    boost::asio::awaitable<void> tick_loop();
    void run_due_ticks();
    // Counts the late and dropped ticks of a batch of `due`, by match and by mode.
    void count_late_ticks(uint32_t due);
    void log_stats(int64_t now);
    uint64_t open_connections() const;
    bool drained() const;  // no connection a shutdown waits for is open
    void finish();
    // High density on Agones: the matches and players now, to the sidecar's Counter and List.
    void publish_density();
    // An Agones allocation asked for a match (its annotations): created here, on the io thread.
    void create_allocated_match(const ops::allocation_request& request);

    boost::asio::io_context io_{1};  // one thread: the match, the transports and ops share it
    host_options options_;
    match::token_check check_token_;  // the --token-secret's, for the matches and the lobby
    match_registry matches_;
    std::map<std::string, ops::histogram> mode_ticks_;  // one match's tick, seconds, by mode
    struct mode_late_ticks {
        uint64_t late = 0;     // match ticks run more than a tick interval after they fell due
        uint64_t dropped = 0;  // match ticks the clock gave up on
    };
    std::map<std::string, mode_late_ticks> mode_late_;  // whole run, by mode
    uint64_t overruns_counted_ = 0;                     // the clock's overruns already counted by mode
    ops::process_counters process_;  // whole run (connections_open and tick_overruns filled when read)
    arena::host::intake intake_{matches_, process_};
    tick_clock clock_;
    boost::asio::steady_timer tick_timer_;
    boost::asio::steady_timer stop_timer_;
    boost::asio::signal_set signals_;
    bool stopping_ = false;
    bool finished_ = false;
    int64_t started_ns_ = 0;
    duration_histogram run_ticks_;
    duration_histogram window_ticks_;
    // The byte counters at the start of the stats window: the window's traffic is the difference.
    uint64_t window_bytes_in_ = 0;
    uint64_t window_bytes_out_ = 0;
    int64_t window_start_ns_ = 0;
    int64_t last_watchdog_ns_ = 0;
    ops::histogram tick_seconds_;
    int64_t last_tick_ns_ = 0;
    ops::ops_service ops_;
    // Last: destroyed first, while the match, the counters and ops_ they hold on to still live.
    std::vector<std::unique_ptr<transport>> transports_;
};

}  // namespace arena::host
