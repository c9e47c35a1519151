#include "client_sim/bot.hpp"

#include <boost/asio/co_spawn.hpp>
#include <boost/asio/detached.hpp>
#include <boost/asio/redirect_error.hpp>
#include <boost/asio/use_awaitable.hpp>
#include <boost/asio/write.hpp>

#include "client_sim/fleet.hpp"

namespace arena::bots {

namespace {

using boost::asio::redirect_error;
using boost::asio::use_awaitable;
using end_kind = client_core::end_kind;

// Bytes per read: several snapshots of a 64-player world at once; 16 MB for 1000 bots.
constexpr std::size_t read_buffer_bytes = 16 * 1024;
// Receive buffer of a slow-reader bot: the kernel's minimum, about two snapshots.
constexpr int slow_reader_buffer_bytes = 4096;

}  // namespace

bot::bot(fleet& owner, client_params params)
    : bot_session(owner, params),
      fleet_(owner),
      slow_reader_(params.mode == misbehavior::slow_reader),
      socket_(owner.io()),
      wake_(owner.io()),
      read_buffer_(read_buffer_bytes) {}

boost::asio::awaitable<void> bot::run() {
    try {
        core_.launch(fleet_.now_ns());
        boost::system::error_code ec;
        if (slow_reader_) {
            // A small receive window (set before connecting, when TCP negotiates window
            // scaling), so that only the server's own send buffer stands between the fault
            // and the server noticing it, not megabytes of our autotuned buffer as well.
            socket_.open(fleet_.endpoint().protocol(), ec);
            socket_.set_option(boost::asio::socket_base::receive_buffer_size(slow_reader_buffer_bytes), ec);
        }
        co_await socket_.async_connect(fleet_.endpoint(), redirect_error(use_awaitable, ec));
        if (core_.ended()) co_return;  // aborted while connecting
        if (ec) {
            core_.on_transport_end(end_kind::transport_error, "connect: " + ec.message());
            sync();
            co_return;
        }
        // Inputs are tiny and due now: never let Nagle hold one back for the next.
        socket_.set_option(boost::asio::ip::tcp::no_delay(true), ec);
        core_.connected();
        boost::asio::co_spawn(socket_.get_executor(), writer(), boost::asio::detached);
        co_await reader();
    } catch (const std::exception& e) {
        // Our bug, not the server's; still ends only this bot.
        core_.on_transport_end(end_kind::protocol_error, std::string("internal error: ") + e.what());
        sync();
    }
}

boost::asio::awaitable<void> bot::reader() {
    boost::system::error_code ec;
    while (!core_.ended()) {
        const std::size_t n =
            co_await socket_.async_read_some(boost::asio::buffer(read_buffer_), redirect_error(use_awaitable, ec));
        if (core_.ended()) co_return;
        if (ec == boost::asio::error::eof) {
            core_.on_transport_end(end_kind::by_server, "server closed the connection without Reject or Bye");
            sync();
            co_return;
        }
        if (ec) {
            core_.on_transport_end(end_kind::transport_error, "read: " + ec.message());
            sync();
            co_return;
        }
        fleet_.count_in(n);
        core_.on_bytes({read_buffer_.data(), n}, fleet_.now_ns());
        sync();
        // The slow-reader fault: leave every later byte in the kernel's buffers, so that the
        // server's outgoing queue for us grows until it gives up on us.
        if (!core_.reading()) co_return;
    }
}

boost::asio::awaitable<void> bot::writer() {
    boost::system::error_code ec;
    while (!core_.ended()) {
        std::vector<std::uint8_t>& queued = core_.output();
        if (queued.empty()) {
            if (core_.closing()) {
                core_.flushed();
                sync();
                co_return;
            }
            wake_.expires_at(boost::asio::steady_timer::time_point::max());
            co_await wake_.async_wait(redirect_error(use_awaitable, ec));
            continue;  // woken (cancelled) by sync()
        }
        // Everything queued goes out in one write; the two buffers keep their capacity.
        std::swap(queued, sending_);
        co_await boost::asio::async_write(socket_, boost::asio::buffer(sending_), redirect_error(use_awaitable, ec));
        if (core_.ended()) co_return;
        if (ec) {
            core_.on_transport_end(end_kind::transport_error, "write: " + ec.message());
            sync();
            co_return;
        }
        fleet_.count_out(sending_.size());
        sending_.clear();
    }
}

void bot::sync() {
    if (core_.ended()) {
        if (!closed_) {
            closed_ = true;
            boost::system::error_code ignored;
            socket_.shutdown(boost::asio::ip::tcp::socket::shutdown_both, ignored);
            socket_.close(ignored);
        }
        wake_.cancel();
        return;
    }
    if (!core_.output().empty() || core_.closing()) wake_.cancel();
}

}  // namespace arena::bots
