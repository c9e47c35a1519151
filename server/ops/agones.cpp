#include "server/ops/agones.hpp"

#include <chrono>

#include "server/ops/backoff.hpp"
#include "server/ops/density_sync.hpp"
#include "server/ops/http_client.hpp"

namespace arena::ops {

agones_client::agones_client(boost::asio::io_context& io, agones_options options, std::function<bool()> healthy,
                             log_fn log)
    : io_(io),
      options_(std::move(options)),
      healthy_(std::move(healthy)),
      log_(std::move(log)),
      wake_(io),
      deadline_(io) {}

agones_client::~agones_client() = default;

void agones_client::keep_density(std::function<void(const allocation_request&)> on_allocation) {
    if (density_) return;
    density_options o;
    o.host = options_.host;
    o.port = options_.port;
    o.request_timeout_ns = options_.request_timeout_ns;
    o.retry_initial_ns = options_.retry_initial_ns;
    o.retry_max_ns = options_.retry_max_ns;
    density_ = std::make_unique<density_sync>(io_, o, log_, std::move(on_allocation));
}

void agones_client::want_density(density_state desired) {
    if (density_) density_->want(std::move(desired));
}

void agones_client::start() {
    if (started_) return;
    started_ = true;
    boost::asio::co_spawn(io_, run(), boost::asio::detached);
    if (density_ && !stopping_) density_->start();
}

void agones_client::shutdown(std::function<void()> done) {
    if (done) done_.push_back(std::move(done));
    if (finished_) {
        finish_shutdown(nullptr);
        return;
    }
    if (stopping_) return;
    stopping_ = true;
    wake_.cancel();                  // out of the backoff or ping wait, on to /shutdown
    if (density_) density_->stop();  // the GameServer goes away with the process
    deadline_.expires_after(std::chrono::nanoseconds(options_.shutdown_timeout_ns));
    deadline_.async_wait([this](const boost::system::error_code& ec) {
        if (!ec) finish_shutdown("timed out");
    });
    start();  // a match that ended before start() still tells Agones
}

void agones_client::finish_shutdown(const char* how) {
    if (how && !finished_ && log_) log_(std::string("agones: shutdown ") + how);
    finished_ = true;
    deadline_.cancel();
    wake_.cancel();
    // Posted: the caller's `done` usually stops the io_context, and must not run inside
    // shutdown() or a timer handler of ours.
    for (auto& done : done_) boost::asio::post(io_, std::move(done));
    done_.clear();
}

boost::asio::awaitable<bool> agones_client::post(const char* path) {
    const http_result r =
        co_await http_post(io_.get_executor(), options_.host, options_.port, path, "{}", options_.request_timeout_ns);
    if (!r.ok() && log_ && !finished_)
        log_(std::string("agones: POST ") + path +
             " failed: " + (r.status ? "HTTP " + std::to_string(r.status) : r.error));
    co_return r.ok();
}

boost::asio::awaitable<void> agones_client::sleep(int64_t ns) {
    wake_.expires_after(std::chrono::nanoseconds(ns));
    boost::system::error_code ec;
    co_await wake_.async_wait(boost::asio::redirect_error(boost::asio::use_awaitable, ec));
}

boost::asio::awaitable<void> agones_client::run() {
    // Ready: the sidecar may start after us (Agones starts the pod's containers together).
    backoff retry(options_.retry_initial_ns, options_.retry_max_ns);
    while (!stopping_) {
        if (co_await post("/ready")) {
            ready_ = true;
            if (log_) log_("agones: ready");
            break;
        }
        if (!stopping_) co_await sleep(retry.next_ns());
    }
    // Health: a missed ping is not retried early; the next one is due soon enough.
    while (!stopping_) {
        if (healthy_ && healthy_() && co_await post("/health")) ++health_pings_;
        if (!stopping_) co_await sleep(options_.health_interval_ns);
    }
    // Shutdown: Agones then deletes the pod; until it answers, retry within the deadline.
    retry.reset();
    while (!finished_) {
        if (co_await post("/shutdown")) {
            finish_shutdown("accepted");
            break;
        }
        if (!finished_) co_await sleep(retry.next_ns());
    }
}

}  // namespace arena::ops
