#pragma once
// What an accept loop does when accept() fails. Out of file descriptors (EMFILE, ENFILE) or
// kernel memory, the connection stays queued and the listening socket stays readable, so a loop
// that retries at once spins at 100 % of a core and logs millions of lines while nothing can
// improve. This pauses accepting instead, 10 ms doubling to 1 s while the errors go on, and logs
// at most one line per 10 s (counting the ones it did not log). An error that belongs to one
// connection (ECONNABORTED: the client gave up while queued) is no reason to pause.
//
// For any Asio accept loop (the ops endpoint's here, the game's TCP one):
//     if (ec) { co_await backoff.pause_after(ec); if (stopping) co_return; continue; }
//     backoff.succeeded();
// pause_after touches nothing of the accept_backoff once its wait has begun, so the loop's owner
// may be gone when it resumes: check for that first.
#include <boost/asio.hpp>
#include <cstdint>
#include <functional>
#include <string>

#include "server/ops/backoff.hpp"

namespace arena::ops {

struct accept_backoff_options {
    int64_t initial_ns = 10'000'000;           // the first pause
    int64_t max_ns = 1'000'000'000;            // pauses double up to this
    int64_t log_interval_ns = 10'000'000'000;  // at most one log line per this
};

class accept_backoff {
public:
    // what: names the listener in the log ("metrics", "game"); log may be empty.
    accept_backoff(std::string what, std::function<void(const std::string&)> log, accept_backoff_options options = {});

    // After a failed accept, at now_ns on a steady clock: how long to pause before the next one
    // (0 for an error of one connection). Logs when the last line is log_interval_ns old.
    int64_t failed(const boost::system::error_code& ec, int64_t now_ns);
    // After an accept that worked: the next run of errors starts again from the first pause.
    void succeeded();
    // failed() with the steady clock, then the pause, on the calling coroutine's executor.
    boost::asio::awaitable<void> pause_after(const boost::system::error_code& ec);

    uint64_t errors() const { return errors_; }  // every failed accept so far
    uint64_t log_lines() const { return log_lines_; }

private:
    std::string what_;
    std::function<void(const std::string&)> log_;
    accept_backoff_options options_;
    backoff pause_;
    uint64_t errors_ = 0;
    uint64_t unlogged_ = 0;    // errors since the last line
    int64_t last_log_ns_ = 0;  // valid once log_lines_ > 0
    uint64_t log_lines_ = 0;
};

// Whether accept() failed for want of a resource the whole process shares (descriptors, kernel
// memory), as opposed to something about the one connection it tried to take.
bool out_of_resources(const boost::system::error_code& ec);

}  // namespace arena::ops
