#include "client_sim/fleet.hpp"

#include <algorithm>
#include <boost/asio/co_spawn.hpp>
#include <boost/asio/detached.hpp>
#include <boost/asio/redirect_error.hpp>
#include <boost/asio/use_awaitable.hpp>
#include <csignal>
#include <cstdio>

#include "client_sim/udp_bot.hpp"
#include "client_sim/ws_bot.hpp"

namespace arena::bots {

namespace {

using boost::asio::redirect_error;
using boost::asio::use_awaitable;
using namespace std::chrono_literals;

// A tick more than this late is dropped, not sent in a burst: a burst of inputs is what the
// server's rate limit exists to refuse.
constexpr std::uint64_t max_catch_up_ticks = 4;
// After the run, how long the bots get to write their Bye and close.
constexpr auto goodbye_grace = 3s;

}  // namespace

fleet::fleet(boost::asio::io_context& io, options opts)
    : io_(io),
      opts_(std::move(opts)),
      tick_timer_(io),
      launch_timer_(io),
      report_timer_(io),
      signals_(io, SIGINT, SIGTERM) {
    bots_.reserve(opts_.bots);
    for (std::uint32_t i = 0; i < opts_.bots; ++i) {
        const misbehavior mode =
            (opts_.misbehave != misbehavior::none && is_misbehaving(i, opts_.bots, opts_.misbehave_share))
                ? opts_.misbehave
                : misbehavior::none;
        client_params params;
        params.index = i;
        params.kind = resolve_behavior(opts_.behavior, i);
        params.mode = mode;
        params.seed = opts_.seed;
        params.name = opts_.name_prefix + "-" + std::to_string(i);
        params.token = token_for(opts_, params.name);
        params.delta_snapshots = !opts_.full_snapshots;
        params.join_match = opts_.match;
        params.join_mode = opts_.mode;
        params.join_timeout = static_cast<time_ns>(opts_.join_timeout * 1e9);
        if (opts_.transport == transport_kind::udp)
            bots_.push_back(std::make_unique<udp_bot>(
                *this, std::move(params), simulated_delay{opts_.simulate_latency_ms, opts_.simulate_jitter_ms}));
        else if (opts_.transport == transport_kind::ws)
            bots_.push_back(std::make_unique<ws_bot>(*this, std::move(params)));
        else
            bots_.push_back(std::make_unique<bot>(*this, std::move(params)));
    }
}

fleet::~fleet() = default;

time_ns fleet::now_ns() const {
    return static_cast<time_ns>(std::chrono::duration_cast<std::chrono::nanoseconds>(clock::now() - start_).count());
}

void fleet::count_in(std::size_t bytes) {
    metrics().bytes_in += bytes;
    metrics().interval_bytes_in += bytes;
}

void fleet::count_out(std::size_t bytes) {
    metrics().bytes_out += bytes;
    metrics().interval_bytes_out += bytes;
}

void fleet::on_joined(const protocol::welcome_info& welcome) {
    client_shared::on_joined(welcome);
    if (tick_rate_ != 0 || stopping()) return;
    tick_rate_ = welcome.tick_rate;
    boost::asio::co_spawn(io_, ticker(), boost::asio::detached);
}

boost::asio::awaitable<void> fleet::run() {
    start_ = clock::now();
    end_ = start_ + std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(opts_.duration));
    boost::asio::ip::tcp::resolver resolver(io_);
    boost::system::error_code ec;
    const auto results =
        co_await resolver.async_resolve(opts_.host, std::to_string(opts_.port), redirect_error(use_awaitable, ec));
    if (ec || results.empty()) {
        const std::string reason = "cannot resolve " + opts_.host + ": " + (ec ? ec.message() : "no address");
        std::fprintf(stderr, "arena-bots: %s\n", reason.c_str());
        for (auto& b : bots_) b->abort(reason);  // none joined: the report fails the run
        co_return;
    }
    endpoint_ = results.begin()->endpoint();
    watch_signals();
    boost::asio::co_spawn(io_, launch(), boost::asio::detached);
    co_await report_loop();
    co_await wind_down();
    signals_.cancel();
}

void fleet::watch_signals() {
    signals_.async_wait([this](const boost::system::error_code& ec, int) {
        if (ec) return;
        if (stopping()) {
            // A second signal: stop waiting for the goodbyes.
            for (auto& b : bots_) b->abort("interrupted");
            return;
        }
        std::fprintf(stderr, "arena-bots: signal received, ending the run\n");
        stop();
        watch_signals();
    });
}

boost::asio::awaitable<void> fleet::launch() {
    const auto start = clock::now();
    boost::system::error_code ec;
    std::size_t next = 0;
    while (next < bots_.size() && !stopping()) {
        // Every bot due by now, not one per wake-up: under load one turn of the event loop
        // can take longer than the interval between two connections.
        const double elapsed = std::chrono::duration<double>(clock::now() - start).count();
        const std::size_t due = opts_.connect_rate > 0
                                    ? std::min(bots_.size(), static_cast<std::size_t>(elapsed * opts_.connect_rate) + 1)
                                    : bots_.size();
        for (; next < due; ++next) {
            boost::asio::co_spawn(io_, bots_[next]->run(), boost::asio::detached);
            ++launched_;
        }
        if (next == bots_.size()) break;
        launch_timer_.expires_at(start + std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(
                                             static_cast<double>(next) / opts_.connect_rate)));
        co_await launch_timer_.async_wait(redirect_error(use_awaitable, ec));
    }
    all_launched_ = true;
}

boost::asio::awaitable<void> fleet::ticker() {
    // Deadlines from the tick count, not from the previous wake-up, so that timer latency
    // never accumulates into drift against the server's clock.
    const auto origin = clock::now();
    const auto due = [&](std::uint64_t tick) {
        return origin + std::chrono::nanoseconds(tick * 1'000'000'000ULL / tick_rate_);
    };
    std::uint64_t tick = 0;
    boost::system::error_code ec;
    while (!stopping()) {
        ++tick;
        tick_timer_.expires_at(due(tick));
        co_await tick_timer_.async_wait(redirect_error(use_awaitable, ec));
        if (stopping()) break;
        const auto now = clock::now();
        if (now > due(tick + max_catch_up_ticks)) {
            // The process lagged (overloaded machine): skip to now rather than burst.
            const auto behind =
                static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(now - origin).count() *
                                           tick_rate_ / 1'000'000'000LL);
            metrics().ticks_skipped += behind - tick;
            tick = behind;
        }
        const time_ns at = now_ns();
        for (auto& b : bots_) b->on_tick(tick, at);
    }
}

void fleet::roll_interval(clock::time_point now, double interval_s) {
    if (!opts_.quiet) {
        const double t = std::chrono::duration<double>(now - start_).count();
        std::printf("%s\n", progress_line(t, playing(), opts_.bots, interval_s, metrics()).c_str());
        std::fflush(stdout);
    }
    // Per-second figures only from whole-enough seconds: a 0.1 s tail would skew them.
    if (interval_s >= 0.5) {
        metrics().snapshots_per_s.add(static_cast<double>(metrics().interval_snapshots) / interval_s);
        metrics().bytes_in_per_s.add(static_cast<double>(metrics().interval_bytes_in) / interval_s);
        metrics().bytes_out_per_s.add(static_cast<double>(metrics().interval_bytes_out) / interval_s);
    }
    metrics().interval_snapshots = 0;
    metrics().interval_bytes_in = 0;
    metrics().interval_bytes_out = 0;
    metrics().interval_rtt_ms.clear();
    metrics().interval_prediction_error_m.clear();
}

boost::asio::awaitable<void> fleet::report_loop() {
    auto last = start_;
    boost::system::error_code ec;
    for (int second = 1; !stopping(); ++second) {
        report_timer_.expires_at(std::min(start_ + std::chrono::seconds(second), end_));
        co_await report_timer_.async_wait(redirect_error(use_awaitable, ec));
        const auto now = clock::now();
        roll_interval(now, std::chrono::duration<double>(now - last).count());
        last = now;
        for (auto& b : bots_) b->check_join_timeout(now_ns());
        const bool everyone_gone = all_launched_ && ended() == launched_;
        if (now >= end_ || everyone_gone) stop();
    }
}

void fleet::stop() {
    if (stopping()) return;
    set_stopping();
    tick_timer_.cancel();
    launch_timer_.cancel();
    report_timer_.cancel();
    for (auto& b : bots_) b->finish();
}

boost::asio::awaitable<void> fleet::wind_down() {
    const auto deadline = clock::now() + goodbye_grace;
    boost::system::error_code ec;
    while (ended() < launched_ && clock::now() < deadline) {
        report_timer_.expires_after(20ms);
        co_await report_timer_.async_wait(redirect_error(use_awaitable, ec));
    }
    for (auto& b : bots_) {
        if (!b->ended()) b->abort("did not close within the grace period");
    }
}

final_report fleet::report() {
    std::vector<bot_outcome> outcomes;
    outcomes.reserve(bots_.size());
    for (const auto& b : bots_) {
        b->add_final_figures(metrics());
        outcomes.push_back(b->outcome());
    }
    const double seconds = std::chrono::duration<double>(clock::now() - start_).count();
    return make_report(metrics(), outcomes, seconds);
}

}  // namespace arena::bots
