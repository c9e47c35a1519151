#include "server/net/ws_session.hpp"

#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <sstream>

#include "server/host/intake.hpp"
#include "server/host/log.hpp"
#include "server/net/web_transport.hpp"

namespace arena::net {

namespace beast = boost::beast;
namespace websocket = beast::websocket;
using protocol::RejectCode;

namespace {

auto use_ec(boost::system::error_code& ec) {
    return boost::asio::redirect_error(boost::asio::use_awaitable, ec);
}

// The largest message: one frame of the largest body a client may send, with its prefix.
constexpr uint64_t max_message_bytes = 4 + uint64_t{protocol::max_client_frame_body};
// Bytes per read: an Input is about 50; a larger message takes several reads.
constexpr size_t read_chunk = 4096;

}  // namespace

ws_session::ws_session(beast::tcp_stream stream, web_transport& owner, uint64_t id, std::string peer)
    : ws_(std::move(stream)),
      owner_(owner),
      id_(id),
      peer_(std::move(peer)),
      output_(owner.host().options().max_control_frames),
      wake_(ws_.get_executor()),
      linger_(ws_.get_executor()) {}

match::match& ws_session::game() {
    return owner_.host().matches().match_of(*this);
}

boost::asio::awaitable<void> ws_session::run(request upgrade, std::vector<uint8_t> leftover) {
    auto self = shared_from_this();
    const host::host_options& o = owner_.host().options();
    // As a TCP session's socket: no Nagle delay for a snapshot behind a small frame, and the
    // kernel's send buffer bounded (--socket-send-buffer), so that a client that does not read
    // shows as a stall instead of megabytes held for it.
    boost::system::error_code option_ec;
    auto& socket = beast::get_lowest_layer(ws_).socket();
    socket.set_option(boost::asio::ip::tcp::no_delay(true), option_ec);
    socket.set_option(boost::asio::socket_base::send_buffer_size(o.socket_send_buffer), option_ec);
    // Beast's own deadlines from here (the stream's expiry must be off for them): the 101 and
    // the closing handshake within the handshake timeout; no idle timeout or keep-alive pings
    // of its own: the match's idle timeout and Pings do that, in the protocol.
    beast::get_lowest_layer(ws_).expires_never();
    websocket::stream_base::timeout timeouts{};
    timeouts.handshake_timeout =
        std::min(o.match.admission.handshake_timeout, std::chrono::nanoseconds(o.close_grace_ns));
    timeouts.idle_timeout = websocket::stream_base::none();
    timeouts.keep_alive_pings = false;
    ws_.set_option(timeouts);
    // permessage-deflate off: a small compressed message could inflate far beyond the limit.
    websocket::permessage_deflate deflate;
    deflate.server_enable = false;
    deflate.client_enable = false;
    ws_.set_option(deflate);
    ws_.set_option(websocket::stream_base::decorator(
        [](websocket::response_type& response) { response.set(beast::http::field::server, "arena-server"); }));
    ws_.read_message_max(max_message_bytes);
    ws_.auto_fragment(false);
    ws_.binary(true);
    ws_.control_callback([this](websocket::frame_type kind, beast::string_view) {
        if (kind == websocket::frame_type::close || ping_refused_ || closing_) return;
        // Each ping costs a pong written back: bounded like the protocol's own Pings.
        const web_options& w = owner_.options();
        if (pings_.take(owner_.host().now_ns(), w.max_ws_pings_per_second, w.ws_ping_burst)) return;
        ping_refused_ = true;
        reject_later({RejectCode::ping_limit,
                      "more than " + std::to_string(w.max_ws_pings_per_second) + " WebSocket pings a second"});
    });

    boost::system::error_code ec;
    if (leftover.empty()) {
        co_await ws_.async_accept(upgrade, use_ec(ec));
    } else {
        // Frames sent in the same write as the upgrade were read with its head: Beast takes
        // the head again with them, parses it and keeps the rest for the first reads (at most
        // its 4 KiB read buffer: more is refused as a buffer overflow, in the log).
        std::ostringstream head;
        head << upgrade.base();
        std::string bytes = head.str();
        bytes.append(reinterpret_cast<const char*>(leftover.data()), leftover.size());
        co_await ws_.async_accept(boost::asio::buffer(bytes), use_ec(ec));
    }
    if (ec) {
        host::log_line("ws: %s: upgrade not completed: %s", peer_.c_str(), ec.message().c_str());
        beast::get_lowest_layer(ws_).socket().close(ec);
        co_return;
    }
    opened_ = true;
    owner_.on_open(self);
    boost::asio::co_spawn(ws_.get_executor(), writer(), [self](std::exception_ptr) {});
    game().connect(*this);  // after the writer started, so that a refused client reads why
    co_await reader();
}

boost::asio::awaitable<void> ws_session::reader() {
    std::array<uint8_t, read_chunk> chunk{};
    while (!closing_) {
        boost::system::error_code ec;
        const size_t n = co_await ws_.async_read_some(boost::asio::buffer(chunk), use_ec(ec));
        if (closing_) co_return;
        if (ec == websocket::error::message_too_big) {
            // Beast refused the frame by its header, before buffering it, and answered with the
            // close code 1009; the Reject below may not get through, the log line does.
            owner_.host().intake().refuse(
                *this,
                {RejectCode::too_large, "a WebSocket message over " + std::to_string(max_message_bytes) + " bytes"});
            co_return;
        }
        if (ec) {
            using kind = match::close_cause::kind;
            const bool closed =
                ec == websocket::error::closed || ec == boost::asio::error::eof || ec == beast::error::timeout;
            const kind what = !closed ? kind::socket_error
                                      : (reader_.buffered() > 0 ? kind::closed_mid_frame : kind::connection_closed);
            game().disconnect(*this, {what, {}, closed ? std::string() : ec.message()});
            close_now();
            co_return;
        }
        if (!ws_.got_binary()) {
            owner_.host().intake().refuse(*this,
                                          {RejectCode::bad_request, "a text message: the protocol is binary frames"});
            co_return;
        }
        owner_.host().intake().count_bytes(n);
        if (!take({chunk.data(), n}, ws_.is_message_done())) co_return;
    }
}

bool ws_session::take(std::span<const uint8_t> data, bool message_done) {
    host::intake& intake = owner_.host().intake();
    while (!data.empty() && !closing_) {
        if (frame_in_message_) {
            intake.refuse(*this, {RejectCode::bad_request, "a WebSocket message holds more than one frame"});
            return false;
        }
        data = data.subspan(reader_.feed(data));
        if (reader_.failed()) {
            intake.refuse_unreadable(*this, reader_);
            return false;
        }
        if (!reader_.has_frame()) break;  // the rest of the frame is in the message's next bytes
        frame_in_message_ = true;
        const bool go_on = intake.take(*this, reader_.frame(), owner_.host().now_ns()).go_on;
        reader_.next();
        if (!go_on) {
            close_after({});  // a Bye from the client; after a refusal this changes nothing
            return false;
        }
    }
    if (closing_) return false;
    if (message_done) {
        if (!frame_in_message_) {
            intake.refuse(*this, {RejectCode::bad_request, reader_.buffered() == 0
                                                               ? std::string("an empty WebSocket message")
                                                               : "a WebSocket message ends inside a frame, after " +
                                                                     std::to_string(reader_.buffered()) + " bytes"});
            return false;
        }
        frame_in_message_ = false;
    }
    return true;
}

boost::asio::awaitable<void> ws_session::writer() {
    boost::system::error_code ec;
    while (!closed_) {
        if (auto bytes = output_.next()) {
            if (!bytes->empty()) {
                co_await ws_.async_write(boost::asio::buffer(bytes->data(), bytes->size()), use_ec(ec));
                if (ec) {
                    if (!closing_) game().disconnect(*this, {match::close_cause::kind::write_failed, {}, ec.message()});
                    close_now();
                    co_return;
                }
                owner_.host().count_out(bytes->size());
            }
            output_.written(owner_.host().now_ns());
        } else if (closing_) {
            // The last word is out: the closing handshake, bounded by the handshake timeout
            // (and the linger timer).
            co_await ws_.async_close(websocket::close_code::normal, use_ec(ec));
            close_now();
            co_return;
        } else {
            wake_.expires_at(boost::asio::steady_timer::time_point::max());
            co_await wake_.async_wait(use_ec(ec));
            ec = {};
        }
    }
}

void ws_session::reject_later(match::rejection why) {
    // Not from inside Beast's read (or a call the match made): the refusal goes through the match.
    boost::asio::post(ws_.get_executor(), [self = shared_from_this(), why = std::move(why)] {
        if (!self->closing_) self->game().reject(*self, why);
    });
}

void ws_session::send(protocol::frame_bytes frame) {
    if (closing_) return;
    if (!output_.push_control(std::move(frame), owner_.host().now_ns())) {
        reject_later({RejectCode::slow_consumer, "too many messages waiting to be sent"});
        return;
    }
    wake_.cancel();
}

void ws_session::send_snapshot(const protocol::snapshot_encoder& snapshot, uint32_t ack_sequence) {
    if (closing_) return;
    output_.put_snapshot(snapshot, ack_sequence, owner_.host().now_ns());
    wake_.cancel();
}

void ws_session::send_snapshot_frame(std::span<const uint8_t> frame) {
    if (closing_) return;
    output_.put_snapshot_frame(frame, owner_.host().now_ns());
    wake_.cancel();
}

void ws_session::close(RejectCode code, std::string_view reason) {
    close_after(protocol::encode_reject(code, reason));
}

void ws_session::close_with_bye(std::string_view reason) {
    close_after(protocol::encode_bye(reason));
}

void ws_session::close_with_result(std::string_view reason, const protocol::match_result& result) {
    close_after(protocol::encode_bye(reason, &result));
}

void ws_session::close_after(protocol::frame_bytes last_frame) {
    if (closing_) return;
    closing_ = true;
    output_.keep_only(std::move(last_frame));
    wake_.cancel();
    linger_.expires_after(std::chrono::nanoseconds(owner_.host().options().close_grace_ns));
    linger_.async_wait([self = shared_from_this()](const boost::system::error_code& e) {
        if (!e) self->close_now();
    });
}

void ws_session::close_now() {
    if (closed_) return;
    closed_ = true;
    closing_ = true;
    boost::system::error_code ec;
    auto& socket = beast::get_lowest_layer(ws_).socket();
    socket.shutdown(boost::asio::ip::tcp::socket::shutdown_both, ec);
    socket.close(ec);
    wake_.cancel();
    linger_.cancel();
    if (opened_) owner_.on_gone(*this);
}

}  // namespace arena::net
