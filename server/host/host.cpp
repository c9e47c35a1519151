#include "server/host/host.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <csignal>

#include "server/host/log.hpp"
#include "server/ops/stats_line.hpp"

namespace arena::host {

using boost::asio::use_awaitable;

namespace {

int64_t steady_now_ns() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

double ms(int64_t ns) {
    return static_cast<double>(ns) / 1e6;
}

// With --token-secret, a token must be signed with it and unexpired (the wall clock is read
// here, outside the match).
match::token_check token_check_of(const host_options& o) {
    if (!o.token_secret) return {};
    return [secret = *o.token_secret](std::string_view token) {
        auto claims = secret.verify(std::string(token), auth::unix_now());
        if (!claims) return result<match::signed_token>::failure(std::move(claims.error));
        return result<match::signed_token>::success({std::move(claims.value.name), std::move(claims.value.match)});
    };
}

// Why a signal ends the run, as the Bye and the log say it. SIGHUP (the terminal closed) and
// SIGUSR1 end it in order, like SIGTERM, instead of killing the process without its stats.
const char* signal_reason(int signo) {
    switch (signo) {
        case SIGINT:
            return "server interrupted (SIGINT)";
        case SIGHUP:
            return "server hung up (SIGHUP)";
        case SIGUSR1:
            return "server stopped (SIGUSR1)";
        default:
            return "server terminated (SIGTERM)";
    }
}

registry_options registry_options_of(const host_options& o) {
    registry_options r;
    r.base = o.match;
    r.modes = o.modes;
    r.default_mode = o.default_mode;
    r.max_matches = std::max<uint32_t>(1, o.max_matches);
    r.threads = std::max(1u, o.threads);
    r.empty_match_ticks = static_cast<uint32_t>(std::max(1.0, o.empty_match_seconds * o.match.tick_rate));
    r.wall_clock_ms = [] {
        return std::chrono::duration_cast<std::chrono::milliseconds>(
                   std::chrono::system_clock::now().time_since_epoch())
            .count();
    };
    return r;
}

}  // namespace

process_host::process_host(const host_options& options, const ops::ops_options& ops)
    : options_(options),
      check_token_(token_check_of(options)),
      matches_(
          registry_options_of(options),
          [](std::string_view line) { log_line("%.*s", static_cast<int>(line.size()), line.data()); }, check_token_),
      clock_(1'000'000'000LL / options.match.tick_rate, options.max_catch_up),
      tick_timer_(io_),
      stop_timer_(io_),
      signals_(io_, SIGINT, SIGTERM, SIGHUP),
      ops_(
          io_, ops, [this] { return metrics_snapshot(); }, [this] { return ticking(); },
          [](const std::string& line) { log_line("%s", line.c_str()); }) {
    signals_.add(SIGUSR1);
    ops_.keep_density([this](const ops::allocation_request& request) { create_allocated_match(request); });
}

process_host::~process_host() = default;

int64_t process_host::now_ns() const {
    return steady_now_ns();
}

lobby_answer process_host::lobby(const lobby_request& request) {
    return answer_lobby(matches_, request, check_token_);
}

void process_host::add(std::unique_ptr<transport> t) {
    transports_.push_back(std::move(t));
}

ops::http_handlers process_host::http_handlers() {
    return ops::http_handlers{[this] { return ops_.metrics_text(); },
                              [this] {
                                  return ticking();
                              }};
}

void process_host::start() {
    watch_signals();
    for (auto& t : transports_) t->start();  // each prints its "listening on HOST:PORT"
    log_line("ready: tick_rate=%u snapshot_rate=%u max_players=%u bodies=%zu mode=%s max_matches=%u",
             options_.match.tick_rate, options_.match.snapshot_rate, default_match().config().admission.max_players,
             default_match().state().bodies().size(), options_.default_mode.c_str(), matches_.options().max_matches);
    warn_about_descriptor_limit();
    started_ns_ = window_start_ns_ = last_watchdog_ns_ = last_tick_ns_ = now_ns();
    boost::asio::co_spawn(io_, tick_loop(), boost::asio::detached);
    if (options_.duration_s > 0) {
        stop_timer_.expires_after(std::chrono::nanoseconds(static_cast<int64_t>(options_.duration_s * 1e9)));
        stop_timer_.async_wait([this](const boost::system::error_code& ec) {
            if (!ec) shutdown("match over (--duration reached)");
        });
    }
    publish_density();
    ops_.start_after_listening();  // binds --metrics-port, then POST /ready to Agones
}

void process_host::publish_density() {
    if (!ops_.keeps_density()) return;
    ops::density_state now;
    now.rooms = static_cast<int64_t>(matches_.size());
    // One value per live player: "MATCH/PLAYER", the player's id in its match.
    for (const auto& [key, hosted] : matches_.matches())
        for (const uint32_t id : hosted.game->live_player_ids())
            now.players.insert(hosted.id + "/" + std::to_string(id));
    ops_.want_density(std::move(now));  // sent only when it changed
}

void process_host::create_allocated_match(const ops::allocation_request& request) {
    const std::string mode = request.mode.empty() ? options_.default_mode : request.mode;
    if (!request.match.empty() && matches_.find(request.match)) {
        log_line("agones: the allocated match %s already runs", request.match.c_str());
    } else if (stopping_) {
        log_line("agones: allocation ignored: shutting down");
    } else if (auto made = matches_.create(mode, true, "", request.match);
               std::holds_alternative<match::rejection>(made)) {
        log_line("agones: the allocated match (mode %s) was not created: %s", mode.c_str(),
                 std::get<match::rejection>(made).detail.c_str());
    }
    // Before the sidecar is asked again: the allocator already counted this match in `rooms`.
    publish_density();
}

void process_host::run() {
    io_.run();      // until drained: Bye sent, recording and stats flushed
    io_.restart();  // the match is over: tell Agones (bounded), then return
    ops_.on_match_end([this] { io_.stop(); });
    io_.run();
}

void process_host::watch_signals() {
    signals_.async_wait([this](const boost::system::error_code& ec, int signo) {
        if (!ec) shutdown(signal_reason(signo));
    });
}

void process_host::warn_about_descriptor_limit() const {
    // Each connection is a descriptor; the listening sockets, the log, a recording and the
    // metrics endpoint's connections need some more (32 is generous).
    rlimit limit{};
    if (::getrlimit(RLIMIT_NOFILE, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return;
    const uint64_t wanted = static_cast<uint64_t>(default_match().rules().connection_limit()) + 32;
    if (wanted > limit.rlim_cur)
        log_line(
            "warning: --max-connections %u (+32 for the server's own files) exceeds the descriptor limit %llu "
            "(ulimit -n): connections beyond it wait in the listen queue",
            default_match().rules().connection_limit(), static_cast<unsigned long long>(limit.rlim_cur));
}

boost::asio::awaitable<void> process_host::tick_loop() {
    clock_.start(now_ns());
    while (!stopping_) {
        const int64_t due = clock_.next_due_ns();
        tick_timer_.expires_at(boost::asio::steady_timer::time_point(std::chrono::nanoseconds(due)));
        boost::system::error_code ec;
        co_await tick_timer_.async_wait(boost::asio::redirect_error(use_awaitable, ec));
        if (stopping_) break;
        run_due_ticks();
    }
}

void process_host::run_due_ticks() {
    const uint32_t due = clock_.advance(now_ns());
    count_late_ticks(due);
    if (due > 0)
        for (auto& t : transports_) t->read_before_tick();
    for (uint32_t i = 0; i < due; ++i) {
        const int64_t begin = now_ns();
        matches_.tick_all([this] { return now_ns(); },
                          [this](const hosted_match& m, int64_t spent) {
                              auto [it, added] = mode_ticks_.try_emplace(m.mode, ops::tick_duration_buckets_s());
                              it->second.observe(static_cast<double>(spent) / 1e9);
                          });
        // The whole tick: every match's (one match's, on a server of one).
        const int64_t spent = now_ns() - begin;
        run_ticks_.add(spent);
        window_ticks_.add(spent);
        tick_seconds_.observe(static_cast<double>(spent) / 1e9);
        if (const std::string over = matches_.default_match_over(); !over.empty()) {
            // The rules' winner and the final scoreboard go out in every Bye.
            shutdown(over);
            return;
        }
    }
    if (due > 0) {
        for (auto& t : transports_) t->flush_after_tick();
        publish_density();  // matches created or ended, players joined or left
    }
    const int64_t now = now_ns();
    if (due > 0) last_tick_ns_ = now;
    if (now - last_watchdog_ns_ >= 250'000'000) {
        last_watchdog_ns_ = now;
        for (auto& t : transports_) t->check_stalls(now);
    }
    if (static_cast<double>(now - window_start_ns_) >= options_.stats_interval_s * 1e9) log_stats(now);
}

void process_host::count_late_ticks(uint32_t due) {
    // Of `due` ticks run at once, all but the last fell due more than a tick interval ago; the
    // clock gave up on those beyond its catch-up bound. Both are the process's, so every match
    // running now counts them, by match and by mode.
    const uint64_t late = due > 1 ? due - 1 : 0;
    const uint64_t dropped = clock_.overruns() - overruns_counted_;
    overruns_counted_ = clock_.overruns();
    if (late == 0 && dropped == 0) return;
    matches_.count_late_ticks(late, dropped);
    for (const auto& [key, hosted] : matches_.matches()) {
        mode_late_ticks& counts = mode_late_[hosted.mode];
        counts.late += late;
        counts.dropped += dropped;
    }
}

void process_host::log_stats(int64_t now) {
    const double seconds = static_cast<double>(now - window_start_ns_) / 1e9;
    ops::process_counters p = process_counters();
    p.window.tick_ms_p50 = ms(window_ticks_.quantile_ns(0.5));
    p.window.tick_ms_p99 = ms(window_ticks_.quantile_ns(0.99));
    p.window.tick_ms_max = ms(window_ticks_.max_ns());
    p.window.bytes_in_per_s = static_cast<double>(p.bytes_in - window_bytes_in_) / seconds;
    p.window.bytes_out_per_s = static_cast<double>(p.bytes_out - window_bytes_out_) / seconds;
    // The same figures as --stats-json and /metrics, through the same report()s.
    ops::stats_line_sink line;
    report(default_match().counters(), line);
    report(p, line);
    log_line("%s", line.line().c_str());
    window_ticks_.clear();
    window_bytes_in_ = p.bytes_in;
    window_bytes_out_ = p.bytes_out;
    window_start_ns_ = now;
}

uint64_t process_host::open_connections() const {
    uint64_t open = 0;
    for (const auto& t : transports_) open += t->open_connections();
    return open;
}

bool process_host::drained() const {
    for (const auto& t : transports_)
        if (t->drains_at_shutdown() && t->open_connections() > 0) return false;
    return true;
}

ops::process_counters process_host::process_counters() const {
    ops::process_counters p = process_;
    p.connections_open = open_connections();
    p.tick_overruns = clock_.overruns();
    return p;
}

ops::server_metrics process_host::metrics_snapshot() const {
    ops::server_metrics m;
    m.tick_duration_s = tick_seconds_;
    m.tick_budget_s = 1.0 / options_.match.tick_rate;
    for (const auto& [key, hosted] : matches_.matches()) {
        ops::mode_figures& f = m.modes[hosted.mode];
        ++f.matches;
        f.players += hosted.game->live_player_count();
    }
    for (const auto& [mode, ticks] : mode_ticks_) m.modes[mode].tick_duration_s = ticks;
    for (const auto& [mode, counts] : mode_late_) {
        m.modes[mode].ticks_late = counts.late;
        m.modes[mode].ticks_dropped = counts.dropped;
    }
    m.figures = [match = matches_.default_match().counters(), process = process_counters()](match::figure_sink& out) {
        report(match, out);
        report(process, out);
    };
    m.draining = stopping_;
    return m;
}

void process_host::connection_opened() {
    process_.connections_peak = std::max<uint64_t>(process_.connections_peak, open_connections());
}

void process_host::connection_closed() {
    if (stopping_ && drained()) finish();
}

void process_host::shutdown(const std::string& reason) {
    if (stopping_) return;
    stopping_ = true;
    log_line("shutting down: %s", reason.c_str());
    for (auto& t : transports_) t->stop();
    tick_timer_.cancel();
    stop_timer_.cancel();
    matches_.shut_down(reason);  // Bye to every connection of every match
    if (drained()) {
        finish();
        return;
    }
    // Connections that cannot flush are closed by their own linger timers; this bounds the rest.
    stop_timer_.expires_after(std::chrono::nanoseconds(options_.close_grace_ns + 100'000'000));
    stop_timer_.async_wait([this](const boost::system::error_code&) { finish(); });
}

void process_host::finish() {
    if (finished_) return;
    finished_ = true;
    stop_timer_.cancel();
    if (on_shutdown) on_shutdown();
    if (!options_.stats_json.empty()) write_stats_json(options_.stats_json);
    log_stats(now_ns());
    io_.stop();
}

}  // namespace arena::host
