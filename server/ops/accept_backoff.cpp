#include "server/ops/accept_backoff.hpp"

#include <cerrno>
#include <chrono>

namespace arena::ops {

bool out_of_resources(const boost::system::error_code& ec) {
    if (ec.category() != boost::system::system_category()) return false;
    const int e = ec.value();
    return e == EMFILE || e == ENFILE || e == ENOBUFS || e == ENOMEM;
}

accept_backoff::accept_backoff(std::string what, std::function<void(const std::string&)> log,
                               accept_backoff_options options)
    : what_(std::move(what)), log_(std::move(log)), options_(options), pause_(options.initial_ns, options.max_ns) {}

int64_t accept_backoff::failed(const boost::system::error_code& ec, int64_t now_ns) {
    ++errors_;
    ++unlogged_;
    const int64_t wait_ns = out_of_resources(ec) ? pause_.next_ns() : 0;
    if (log_lines_ == 0 || now_ns - last_log_ns_ >= options_.log_interval_ns) {
        std::string line = what_ + ": accept failed: " + ec.message();
        if (unlogged_ > 1) line += " (" + std::to_string(unlogged_) + " errors since the last line)";
        if (wait_ns > 0) line += "; pausing accepts for " + std::to_string(wait_ns / 1'000'000) + " ms";
        if (log_) log_(line);
        ++log_lines_;
        last_log_ns_ = now_ns;
        unlogged_ = 0;
    }
    return wait_ns;
}

void accept_backoff::succeeded() {
    pause_.reset();
}

boost::asio::awaitable<void> accept_backoff::pause_after(const boost::system::error_code& ec) {
    const auto now = std::chrono::steady_clock::now().time_since_epoch();
    const int64_t wait_ns = failed(ec, std::chrono::duration_cast<std::chrono::nanoseconds>(now).count());
    if (wait_ns <= 0) co_return;
    // The timer lives in this frame, not in *this: the owner may be destroyed during the pause.
    boost::asio::steady_timer timer(co_await boost::asio::this_coro::executor, std::chrono::nanoseconds(wait_ns));
    boost::system::error_code ignored;
    co_await timer.async_wait(boost::asio::redirect_error(boost::asio::use_awaitable, ignored));
}

}  // namespace arena::ops
