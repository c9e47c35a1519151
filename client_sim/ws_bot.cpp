#include "client_sim/ws_bot.hpp"

#include <boost/asio/co_spawn.hpp>
#include <boost/asio/detached.hpp>
#include <boost/asio/redirect_error.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/use_awaitable.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>

#include "client_sim/fleet.hpp"

namespace arena::bots {

namespace beast = boost::beast;
namespace websocket = beast::websocket;

namespace {

using boost::asio::redirect_error;
using boost::asio::use_awaitable;
using end_kind = client_core::end_kind;

// What a frame's 4-byte little-endian prefix says it holds, prefix included; the rest of
// `bytes` when it says more than there is (the core queues whole frames, so it never does).
std::size_t frame_size(std::span<const std::uint8_t> bytes) {
    if (bytes.size() < 4) return bytes.size();
    const std::size_t body = static_cast<std::size_t>(bytes[0]) | (static_cast<std::size_t>(bytes[1]) << 8) |
                             (static_cast<std::size_t>(bytes[2]) << 16) | (static_cast<std::size_t>(bytes[3]) << 24);
    return body <= bytes.size() - 4 ? body + 4 : bytes.size();
}

}  // namespace

struct ws_bot::io {
    explicit io(boost::asio::io_context& context) : ws(context), wake(context) {}
    websocket::stream<beast::tcp_stream> ws;
    boost::asio::steady_timer wake;  // the writer sleeps on it; sync() cancels it
    beast::flat_buffer incoming;
    std::vector<std::uint8_t> sending;  // frames being written; swapped with the core's output
};

ws_bot::ws_bot(fleet& owner, client_params params)
    : bot_session(owner, params), fleet_(owner), io_(std::make_unique<io>(owner.io())) {}

ws_bot::~ws_bot() = default;

boost::asio::awaitable<void> ws_bot::run() {
    try {
        core_.launch(fleet_.now_ns());
        boost::system::error_code ec;
        auto& stream = beast::get_lowest_layer(io_->ws);
        co_await stream.socket().async_connect(fleet_.endpoint(), redirect_error(use_awaitable, ec));
        if (core_.ended()) co_return;  // aborted while connecting
        if (ec) {
            core_.on_transport_end(end_kind::transport_error, "connect: " + ec.message());
            sync();
            co_return;
        }
        stream.socket().set_option(boost::asio::ip::tcp::no_delay(true), ec);
        // Beast's deadlines for the opening and closing handshakes; none while playing (the
        // core's join timeout and the server's Bye or Reject end a session).
        websocket::stream_base::timeout timeouts{};
        timeouts.handshake_timeout = std::chrono::seconds(5);
        timeouts.idle_timeout = websocket::stream_base::none();
        timeouts.keep_alive_pings = false;
        io_->ws.set_option(timeouts);
        io_->ws.read_message_max(4 + std::uint64_t{protocol::max_server_frame_body});
        const auto& at = fleet_.endpoint();
        co_await io_->ws.async_handshake(at.address().to_string() + ":" + std::to_string(at.port()), "/ws",
                                         redirect_error(use_awaitable, ec));
        if (core_.ended()) co_return;
        if (ec) {
            core_.on_transport_end(end_kind::transport_error, "WebSocket upgrade of /ws: " + ec.message());
            sync();
            co_return;
        }
        open_ = true;
        io_->ws.binary(true);
        core_.connected();
        boost::asio::co_spawn(io_->ws.get_executor(), writer(), boost::asio::detached);
        co_await reader();
    } catch (const std::exception& e) {
        core_.on_transport_end(end_kind::protocol_error, std::string("internal error: ") + e.what());
        sync();
    }
}

boost::asio::awaitable<void> ws_bot::reader() {
    boost::system::error_code ec;
    while (!core_.ended()) {
        io_->incoming.clear();
        const std::size_t n = co_await io_->ws.async_read(io_->incoming, redirect_error(use_awaitable, ec));
        if (core_.ended()) co_return;
        if (ec == websocket::error::closed || ec == boost::asio::error::eof) {
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
        const auto data = io_->incoming.cdata();
        core_.on_frame({static_cast<const std::uint8_t*>(data.data()), data.size()}, fleet_.now_ns());
        sync();
        if (!core_.reading()) co_return;  // the slow-reader fault: leave the rest unread
    }
}

boost::asio::awaitable<void> ws_bot::writer() {
    boost::system::error_code ec;
    while (!core_.ended()) {
        std::vector<std::uint8_t>& queued = core_.output();
        if (queued.empty()) {
            if (core_.closing()) {
                // The last frame (a Bye) is out: the closing handshake, bounded by Beast's timeout.
                co_await io_->ws.async_close(websocket::close_code::normal, redirect_error(use_awaitable, ec));
                core_.flushed();
                sync();
                co_return;
            }
            io_->wake.expires_at(boost::asio::steady_timer::time_point::max());
            co_await io_->wake.async_wait(redirect_error(use_awaitable, ec));
            ec = {};
            continue;  // woken (cancelled) by sync()
        }
        // One binary message per frame; the two buffers keep their capacity.
        std::swap(queued, io_->sending);
        std::span<const std::uint8_t> rest(io_->sending);
        while (!rest.empty() && !ec) {
            const std::size_t size = frame_size(rest);
            co_await io_->ws.async_write(boost::asio::buffer(rest.data(), size), redirect_error(use_awaitable, ec));
            rest = rest.subspan(size);
        }
        if (core_.ended()) co_return;
        if (ec) {
            core_.on_transport_end(end_kind::transport_error, "write: " + ec.message());
            sync();
            co_return;
        }
        fleet_.count_out(io_->sending.size());
        io_->sending.clear();
    }
}

void ws_bot::sync() {
    if (core_.ended()) {
        if (!closed_) {
            closed_ = true;
            boost::system::error_code ignored;
            auto& socket = beast::get_lowest_layer(io_->ws).socket();
            socket.shutdown(boost::asio::ip::tcp::socket::shutdown_both, ignored);
            socket.close(ignored);
        }
        io_->wake.cancel();
        return;
    }
    if (!core_.output().empty() || core_.closing()) io_->wake.cancel();
}

}  // namespace arena::bots
