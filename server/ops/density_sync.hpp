#pragma once
// Keeps the sidecar's Counter `rooms` and List `players` true (density_reconciler.hpp says
// what to send; this sends it, one request at a time, and retries failures with backoff), and
// watches the GameServer (GET /watch/gameserver) for allocations: each new
// agones.dev/last-allocated asks the process for the match its annotations name. The
// allocator has already counted that match in `rooms`, so the counter is re-read rather than
// incremented: level-triggered, it ends equal to the number of matches either way.
// Header-only (inline), included by agones.cpp and the tests alone.
#include <boost/asio.hpp>

#include <chrono>
#include <functional>
#include <memory>
#include <set>
#include <string>

#include "server/ops/agones_json.hpp"
#include "server/ops/backoff.hpp"
#include "server/ops/density_reconciler.hpp"
#include "server/ops/http_client.hpp"

namespace arena::ops {

struct density_options {
    std::string host = "127.0.0.1";
    uint16_t port = 9358;
    int64_t request_timeout_ns = 1'000'000'000;  // one request, connect to whole answer
    int64_t retry_initial_ns = 100'000'000;      // first wait after a failed request or a dropped watch
    int64_t retry_max_ns = 2'000'000'000;        // waits double up to this
};

class density_sync {
public:
    using log_fn = std::function<void(const std::string&)>;
    using allocation_fn = std::function<void(const allocation_request&)>;

    density_sync(boost::asio::io_context& io, density_options options, log_fn log, allocation_fn on_allocation)
        : io_(io),
          options_(std::move(options)),
          log_(std::move(log)),
          on_allocation_(std::move(on_allocation)),
          idle_(io),
          pause_(io),
          watch_pause_(io),
          alive_(std::make_shared<bool>(true)) {}
    ~density_sync() {
        stop();
        *alive_ = false;
    }
    density_sync(const density_sync&) = delete;
    density_sync& operator=(const density_sync&) = delete;

    void start() {
        if (started_) return;
        started_ = true;
        boost::asio::co_spawn(io_, send_loop(), boost::asio::detached);
        boost::asio::co_spawn(io_, watch_loop(), boost::asio::detached);
    }
    // Stops sending and closes the watch (the process is shutting down).
    void stop() {
        stopped_ = true;
        idle_.cancel();
        pause_.cancel();
        watch_pause_.cancel();
        if (watch_) watch_->close();
    }
    // What the process holds now; the sidecar is brought to it.
    void want(density_state desired) {
        if (desired == reconciler_.desired()) return;
        reconciler_.want(std::move(desired));
        idle_.cancel();
    }

    const density_reconciler& reconciler() const { return reconciler_; }
    uint64_t allocations() const { return allocations_; }

private:
    static std::string path_of(const sidecar_call& call) {
        using k = sidecar_call::kind;
        switch (call.what) {
            case k::read_rooms:
            case k::change_rooms:
                return "/v1beta1/counters/rooms";
            case k::read_players:
                return "/v1beta1/lists/players";
            case k::add_player:
                return "/v1beta1/lists/players:addValue";
            case k::remove_player:
                return "/v1beta1/lists/players:removeValue";
        }
        return "/";
    }

    boost::asio::awaitable<void> send_loop() {
        const std::shared_ptr<bool> alive = alive_;
        backoff retry(options_.retry_initial_ns, options_.retry_max_ns);
        while (*alive && !stopped_) {
            const std::optional<sidecar_call> call = reconciler_.next();
            if (!call) {
                co_await wait(idle_, int64_t{3'600'000'000'000});  // until want() or the watch
                continue;
            }
            const sidecar_outcome outcome = co_await send(*call);
            if (!*alive) co_return;
            if (outcome == sidecar_outcome::failed) {
                co_await wait(pause_, retry.next_ns());
            } else {
                retry.reset();
            }
        }
    }

    boost::asio::awaitable<sidecar_outcome> send(const sidecar_call& call) {
        using k = sidecar_call::kind;
        const std::shared_ptr<bool> alive = alive_;
        const bool read = call.what == k::read_rooms || call.what == k::read_players;
        const std::string method = read ? "GET" : call.what == k::change_rooms ? "PATCH" : "POST";
        const std::string body = call.what == k::change_rooms ? agones_json::count_diff_body(call.diff)
                                 : read                       ? std::string()
                                                              : agones_json::list_value_body(call.value);
        const std::string path = path_of(call);
        const http_result r = co_await http_call(io_.get_executor(), method, options_.host, options_.port, path, body,
                                                 options_.request_timeout_ns);
        if (!*alive) co_return sidecar_outcome::failed;
        sidecar_outcome outcome = sidecar_outcome::failed;
        int64_t count = 0;
        std::vector<std::string> values;
        if (r.ok()) {
            // A PATCH's answer is ignored: before Agones 1.54 it is an empty Counter.
            outcome = sidecar_outcome::done;
            if (call.what == k::read_rooms) {
                const auto c = agones_json::counter_count(r.body);
                outcome = c ? sidecar_outcome::done : sidecar_outcome::failed;
                count = c.value_or(0);
            } else if (call.what == k::read_players) {
                auto v = agones_json::list_values(r.body);
                outcome = v ? sidecar_outcome::done : sidecar_outcome::failed;
                if (v) values = std::move(*v);
            }
        } else if (agones_json::says_unknown_key(r.body) || (read && (r.status == 404 || r.status == 501))) {
            // A read is the first call about a key: a sidecar without Counters and Lists at
            // all (no such route) answers it 404 or 501.
            outcome = sidecar_outcome::unknown_key;
        } else if ((call.what == k::add_player && r.body.find("already exists") != std::string::npos) ||
                   (call.what == k::remove_player && r.body.find("not found") != std::string::npos)) {
            outcome = sidecar_outcome::done;  // the List already holds what we wanted
        }
        if (outcome == sidecar_outcome::failed) {
            const std::string why = method + " " + path + " failed: " +
                                    (r.status ? "HTTP " + std::to_string(r.status) + " " + r.body : r.error);
            // Once per kind of failure, not once per retry.
            if (why != last_failure_ && log_) log_("agones: " + why);
            last_failure_ = why;
        } else {
            last_failure_.clear();
        }
        const bool had_rooms = reconciler_.rooms_enabled(), had_players = reconciler_.players_enabled();
        reconciler_.answered(call, outcome, count, values);
        log_keys_dropped(had_rooms, had_players);
        co_return outcome;
    }

    boost::asio::awaitable<void> watch_loop() {
        const std::shared_ptr<bool> alive = alive_;
        backoff retry(options_.retry_initial_ns, options_.retry_max_ns);
        std::string last_why;
        while (*alive && !stopped_) {
            http_line_stream stream(io_.get_executor());
            watch_ = &stream;
            bool heard = false;
            const http_result r =
                co_await stream.run(options_.host, options_.port, "/watch/gameserver", options_.request_timeout_ns,
                                    [this, &heard](std::string_view line) {
                                        heard = true;
                                        on_watch_line(line);
                                    });
            if (!*alive) co_return;
            watch_ = nullptr;
            if (stopped_) break;
            if (heard) retry.reset();
            const std::string why = r.status && !r.ok() ? "HTTP " + std::to_string(r.status) : r.error;
            if (why != last_why && log_) log_("agones: the GameServer watch ended (" + why + "), reconnecting");
            last_why = why;
            co_await wait(watch_pause_, retry.next_ns());
        }
    }

    void on_watch_line(std::string_view line) {
        const std::optional<gameserver_view> gs = agones_json::watch_event(line);
        if (!gs) return;
        if (!gs->last_allocated.empty() && gs->last_allocated != last_allocated_) {
            last_allocated_ = gs->last_allocated;
            ++allocations_;
            if (log_)
                log_("agones: allocated (mode=" + (gs->mode.empty() ? std::string("default") : gs->mode) +
                     " match=" + (gs->match.empty() ? std::string("new") : gs->match) + ")");
            // The process creates the match and says so through want() before we go on.
            if (on_allocation_) on_allocation_(allocation_request{gs->mode, gs->match});
        }
        const bool had_rooms = reconciler_.rooms_enabled(), had_players = reconciler_.players_enabled();
        reconciler_.observed(gs->rooms_count, gs->players_declared);
        log_keys_dropped(had_rooms, had_players);
        idle_.cancel();
    }

    // Once per key, whether the sidecar's answer or the GameServer's status said it.
    void log_keys_dropped(bool had_rooms, bool had_players) {
        if (!log_) return;
        if (had_rooms && !reconciler_.rooms_enabled())
            log_("agones: the GameServer declares no Counter 'rooms': it is not kept (see deploy/README.md)");
        if (had_players && !reconciler_.players_enabled())
            log_("agones: the GameServer declares no List 'players': it is not kept (see deploy/README.md)");
    }

    boost::asio::awaitable<void> wait(boost::asio::steady_timer& timer, int64_t ns) {
        timer.expires_after(std::chrono::nanoseconds(ns));
        boost::system::error_code ec;
        co_await timer.async_wait(boost::asio::redirect_error(boost::asio::use_awaitable, ec));
    }

    boost::asio::io_context& io_;
    density_options options_;
    log_fn log_;
    allocation_fn on_allocation_;
    density_reconciler reconciler_;
    boost::asio::steady_timer idle_;         // the send loop waits here while in sync
    boost::asio::steady_timer pause_;        // the wait after a failed request (want() does not cut it)
    boost::asio::steady_timer watch_pause_;  // the wait before reconnecting the watch
    http_line_stream* watch_ = nullptr;      // the watch's connection, for stop()
    std::shared_ptr<bool> alive_;            // false once destroyed: a coroutine resumed late stops
    bool started_ = false;
    bool stopped_ = false;
    std::string last_allocated_;
    std::string last_failure_;
    uint64_t allocations_ = 0;
};

}  // namespace arena::ops
