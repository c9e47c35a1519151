#include "server/net/server.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "protocol/version.hpp"
#include "server/config/scoreboard_json.hpp"
#include "server/net/log.hpp"
#include "server/net/session.hpp"
#include "server/net/stats_json.hpp"
#include "server/ops/stats_line.hpp"

namespace arena::net {

using boost::asio::use_awaitable;
using boost::asio::ip::tcp;

namespace {

int64_t steady_now_ns() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

double ms(int64_t ns) {
    return static_cast<double>(ns) / 1e6;
}

// CPU time and peak memory of this process, for the benchmarks and capacity planning.
nlohmann::json process_figures() {
    rusage usage{};
    ::getrusage(RUSAGE_SELF, &usage);
    auto seconds = [](const timeval& t) {
        return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_usec) / 1e6;
    };
    return {{"cpu_user_s", seconds(usage.ru_utime)},
            {"cpu_system_s", seconds(usage.ru_stime)},
            {"peak_rss_kib", usage.ru_maxrss}};
}

// The match's configuration: its own, and the admission limits the server's flags set.
match::match_config match_config_of(const server_options& o) {
    match::match_config c = o.match;
    c.max_connections = o.max_connections;
    c.max_pending_handshakes = o.max_pending_handshakes;
    c.handshake_timeout_s = static_cast<double>(o.handshake_timeout_ns) / 1e9;
    c.idle_timeout_s = static_cast<double>(o.idle_timeout_ns) / 1e9;
    return c;
}

// With --token-secret, a token must be signed with it and unexpired (the wall clock is read
// here, outside the match).
match::token_check token_check_of(const server_options& o) {
    if (!o.token_secret) return {};
    return [secret = *o.token_secret](std::string_view token) {
        auto claims = secret.verify(std::string(token), auth::unix_now());
        if (auto* e = std::get_if<auth::token_error>(&claims)) return match::token_verdict{std::nullopt, e->reason};
        return match::token_verdict{std::get<auth::token_claims>(claims).name, {}};
    };
}

}  // namespace

server::server(boost::asio::io_context& io, const server_options& options, const world::world_config& world_config)
    : io_(io),
      options_(options),
      match_(match_config_of(options), world_config, server_logger(), token_check_of(options)),
      acceptor_(io),
      accept_backoff_("game", [](const std::string& line) { log_line("%s", line.c_str()); }),
      clock_(1'000'000'000LL / options.match.tick_rate, options.max_catch_up),
      tick_timer_(io),
      stop_timer_(io) {}

int64_t server::now_ns() const {
    return steady_now_ns();
}

void server::start() {
    const tcp::endpoint endpoint(boost::asio::ip::make_address(options_.bind), options_.port);
    acceptor_.open(endpoint.protocol());
    acceptor_.set_option(tcp::acceptor::reuse_address(true));
    acceptor_.bind(endpoint);
    acceptor_.listen(boost::asio::socket_base::max_listen_connections);
    port_ = acceptor_.local_endpoint().port();
    std::printf("listening on %s:%u\n", options_.bind.c_str(), port_);
    std::fflush(stdout);
    log_line("ready: tick_rate=%u snapshot_rate=%u max_players=%u bodies=%zu", options_.match.tick_rate,
             options_.match.snapshot_rate, options_.match.max_players, match_.state().bodies().size());
    warn_about_descriptor_limit();
    started_ns_ = window_start_ns_ = last_watchdog_ns_ = last_tick_ns_ = now_ns();
    boost::asio::co_spawn(io_, accept_loop(), boost::asio::detached);
    boost::asio::co_spawn(io_, tick_loop(), boost::asio::detached);
    if (options_.duration_s > 0) {
        stop_timer_.expires_after(std::chrono::nanoseconds(static_cast<int64_t>(options_.duration_s * 1e9)));
        stop_timer_.async_wait([this](const boost::system::error_code& ec) {
            if (!ec) shutdown("match over (--duration reached)");
        });
    }
}

void server::warn_about_descriptor_limit() const {
    // Each connection is a descriptor; the listening sockets, the log, a recording and the
    // metrics endpoint's connections need some more (32 is generous).
    rlimit limit{};
    if (::getrlimit(RLIMIT_NOFILE, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return;
    const uint64_t wanted = static_cast<uint64_t>(match_.rules().connection_limit()) + 32;
    if (wanted > limit.rlim_cur)
        log_line(
            "warning: --max-connections %u (+32 for the server's own files) exceeds the descriptor limit %llu "
            "(ulimit -n): connections beyond it wait in the listen queue",
            match_.rules().connection_limit(), static_cast<unsigned long long>(limit.rlim_cur));
}

boost::asio::awaitable<void> server::accept_loop() {
    while (!stopping_) {
        boost::system::error_code ec;
        tcp::socket socket = co_await acceptor_.async_accept(boost::asio::redirect_error(use_awaitable, ec));
        if (ec) {
            if (stopping_ || ec == boost::asio::error::operation_aborted) co_return;
            // Out of descriptors the connection stays queued and accept fails again at once:
            // retrying at once spun a core and logged millions of lines. Pause instead.
            co_await accept_backoff_.pause_after(ec);
            if (stopping_) co_return;
            continue;
        }
        accept_backoff_.succeeded();
        auto s = std::make_shared<session>(std::move(socket), *this, match_, next_session_id_++);
        sessions_.push_back(s);
        ++open_sessions_;
        process_.connections_peak = std::max<uint64_t>(process_.connections_peak, open_connections());
        s->start();
        match_.connect(*s);  // after start(), so that a refused client reads why
    }
}

boost::asio::awaitable<void> server::tick_loop() {
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

void server::read_sessions() {
    // By index: a session that closes while it reads leaves a null (on_gone), and none is added.
    reading_sessions_ = true;
    for (size_t i = 0; i < sessions_.size(); ++i)
        if (session* s = sessions_[i].get()) s->read_available(read_buffer_);
    reading_sessions_ = false;
    if (!gone_.empty()) {
        std::erase(sessions_, nullptr);
        gone_.clear();
    }
}

void server::request_flush(std::shared_ptr<session> s) {
    to_flush_.push_back(std::move(s));
    if (flush_posted_) return;
    flush_posted_ = true;
    boost::asio::post(io_, [this] { flush_sessions(); });
}

void server::flush_sessions() {
    flush_posted_ = false;
    flushing_.swap(to_flush_);
    for (auto& s : flushing_) s->flush();
    flushing_.clear();
}

void server::run_due_ticks() {
    const uint32_t due = clock_.advance(now_ns());
    if (due > 0) read_sessions();
    for (uint32_t i = 0; i < due; ++i) {
        const int64_t begin = now_ns();
        match_.tick();
        const int64_t spent = now_ns() - begin;
        run_ticks_.add(spent);
        window_ticks_.add(spent);
        tick_seconds_.observe(static_cast<double>(spent) / 1e9);
        if (match_.over()) {
            // The rules' winner and the final scoreboard go out in every Bye.
            shutdown("match over (--score-limit reached)");
            return;
        }
    }
    const int64_t now = now_ns();
    if (due > 0) last_tick_ns_ = now;
    if (now - last_watchdog_ns_ >= 250'000'000) check_stalled_sessions(now);
    if (static_cast<double>(now - window_start_ns_) >= options_.stats_interval_s * 1e9) log_stats(now);
}

void server::check_stalled_sessions(int64_t now) {
    last_watchdog_ns_ = now;
    std::vector<std::shared_ptr<session>> stalled;
    for (auto& s : sessions_)
        if (s && !s->closing() && s->stalled_ns(now) > options_.stall_timeout_ns) stalled.push_back(s);
    for (auto& s : stalled)
        match_.reject(*s, {protocol::RejectCode::slow_consumer, "no progress writing to the client"});
}

void server::log_stats(int64_t now) {
    const double seconds = static_cast<double>(now - window_start_ns_) / 1e9;
    ops::process_counters p = process_counters();
    p.window.tick_ms_p50 = ms(window_ticks_.quantile_ns(0.5));
    p.window.tick_ms_p99 = ms(window_ticks_.quantile_ns(0.99));
    p.window.tick_ms_max = ms(window_ticks_.max_ns());
    p.window.bytes_in_per_s = static_cast<double>(window_traffic_.bytes_in) / seconds;
    p.window.bytes_out_per_s = static_cast<double>(window_traffic_.bytes_out) / seconds;
    // The same figures as --stats-json and /metrics, through the same report()s.
    ops::stats_line_sink line;
    report(match_.counters(), line);
    report(p, line);
    log_line("%s", line.line().c_str());
    window_ticks_.clear();
    window_traffic_ = {};
    window_start_ns_ = now;
}

ops::process_counters server::process_counters() const {
    ops::process_counters p = process_;
    p.connections_open = open_connections();
    p.tick_overruns = clock_.overruns();
    return p;
}

ops::server_metrics server::metrics_snapshot() const {
    ops::server_metrics m;
    m.tick_duration_s = tick_seconds_;
    m.tick_budget_s = 1.0 / options_.match.tick_rate;
    m.figures = [match = match_.counters(), process = process_counters()](match::figure_sink& out) {
        report(match, out);
        report(process, out);
    };
    m.draining = stopping_;
    return m;
}

void server::on_gone(session& s) {
    const auto it = std::find_if(sessions_.begin(), sessions_.end(), [&](const auto& p) { return p.get() == &s; });
    if (it != sessions_.end()) {
        --open_sessions_;
        if (reading_sessions_)
            gone_.push_back(std::move(*it));  // alive until read_sessions() ends: it may be reading
        else
            sessions_.erase(it);
    }
    if (stopping_ && open_sessions_ == 0 && other_open_ == 0) finish();
}

void server::transport_opened() {
    ++other_open_;
    process_.connections_peak = std::max<uint64_t>(process_.connections_peak, open_connections());
}

void server::transport_closed() {
    if (other_open_ > 0) --other_open_;
    if (stopping_ && open_sessions_ == 0 && other_open_ == 0) finish();
}

void server::count_peer_opened() {
    ++peers_open_;
    process_.connections_peak = std::max<uint64_t>(process_.connections_peak, open_connections());
}

void server::count_peer_closed() {
    if (peers_open_ > 0) --peers_open_;
}

void server::count_in(size_t bytes) {
    process_.bytes_in += bytes;
    window_traffic_.bytes_in += bytes;
}

void server::count_out(size_t bytes) {
    count_out(bytes, 1);
}

void server::count_out(size_t bytes, size_t messages) {
    process_.bytes_out += bytes;
    window_traffic_.bytes_out += bytes;
    process_.messages_out += messages;
}

void server::shutdown(const std::string& reason) {
    if (stopping_) return;
    stopping_ = true;
    log_line("shutting down: %s", reason.c_str());
    boost::system::error_code ec;
    acceptor_.close(ec);
    tick_timer_.cancel();
    stop_timer_.cancel();
    match_.shut_down(reason);  // Bye to every connection
    if (open_sessions_ == 0 && other_open_ == 0) {
        finish();
        return;
    }
    // Sessions that cannot flush are closed by their own linger timers; this bounds the rest.
    stop_timer_.expires_after(std::chrono::nanoseconds(options_.close_grace_ns + 100'000'000));
    stop_timer_.async_wait([this](const boost::system::error_code&) { finish(); });
}

void server::finish() {
    if (finished_) return;
    finished_ = true;
    stop_timer_.cancel();
    if (on_shutdown) on_shutdown();
    if (!options_.stats_json.empty()) write_stats_json(options_.stats_json);
    log_stats(now_ns());
    io_.stop();
}

void server::write_stats_json(const std::string& path) const {
    const double seconds = static_cast<double>(now_ns() - started_ns_) / 1e9;
    const ops::process_counters p = process_counters();
    nlohmann::json j = {
        {"duration_s", seconds},
        {"tick_rate", options_.match.tick_rate},
        {"snapshot_rate", options_.match.snapshot_rate},
        {"tick_ms",
         {{"p50", ms(run_ticks_.quantile_ns(0.5))},
          {"p99", ms(run_ticks_.quantile_ns(0.99))},
          {"max", ms(run_ticks_.max_ns())},
          {"mean", run_ticks_.mean_ns() / 1e6}}},
        {"snapshots", {{"view_radius", options_.match.view_radius}}},
        {"limits",
         {{"max_players", options_.match.max_players},
          {"max_spectators", options_.match.max_spectators},
          {"max_connections", match_.rules().connection_limit()},
          {"max_pending_handshakes", match_.rules().pending_limit()},
          {"max_inputs_per_second", match_.rules().input_limit()},
          {"input_buffer", options_.match.input_buffer},
          {"max_frame_bytes", protocol::max_client_frame_body},
          {"max_control_frames", options_.max_control_frames},
          {"socket_send_buffer", options_.socket_send_buffer},
          {"handshake_timeout_s", static_cast<double>(options_.handshake_timeout_ns) / 1e9},
          {"idle_timeout_s", static_cast<double>(options_.idle_timeout_ns) / 1e9},
          {"stall_timeout_s", static_cast<double>(options_.stall_timeout_ns) / 1e9}}},
        {"process", process_figures()},
        {"bytes_in_per_s", seconds > 0 ? static_cast<double>(p.bytes_in) / seconds : 0},
        {"bytes_out_per_s", seconds > 0 ? static_cast<double>(p.bytes_out) / seconds : 0},
    };
    // Every counter, as the match and the process name them (the same list /metrics reads).
    // The game's scoreboard (an empty array under sandbox rules), as arena-replay --scoreboard prints it.
    std::vector<rules::score_line> lines;
    std::vector<std::string> names;
    for (const match::match::named_score& s : match_.scoreboard()) {
        lines.push_back(s.line);
        names.push_back(s.name);
    }
    j["scoreboard"] = nlohmann::json::parse(config::scoreboard_json(lines, names));
    // The player the rules declare the winner, as every client's last Bye says (0: nobody).
    j["winner"] = match_.game_rules().winner();
    stats_json_sink figures(j);
    report(match_.counters(), figures);
    report(p, figures);
    std::ofstream out(path);
    out << j.dump(2) << "\n";
    if (!out) log_line("cannot write stats to %s", path.c_str());
}

}  // namespace arena::net
