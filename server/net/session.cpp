#include "server/net/session.hpp"

#include "protocol/verify.hpp"
#include "server/net/log.hpp"
#include "server/net/server.hpp"

namespace arena::net {

using boost::asio::use_awaitable;
using protocol::RejectCode;

namespace {

std::string describe(const boost::asio::ip::tcp::socket& socket) {
    boost::system::error_code ec;
    const auto endpoint = socket.remote_endpoint(ec);
    if (ec) return "unknown-peer";
    return endpoint.address().to_string() + ":" + std::to_string(endpoint.port());
}

}  // namespace

session::session(boost::asio::ip::tcp::socket socket, server& owner, match::match& match, uint64_t id)
    : socket_(std::move(socket)),
      owner_(owner),
      match_(match),
      id_(id),
      peer_(describe(socket_)),
      output_(owner.options().max_control_frames),
      wake_(socket_.get_executor()),
      linger_(socket_.get_executor()) {}

void session::start() {
    boost::system::error_code ec;
    socket_.set_option(boost::asio::ip::tcp::no_delay(true), ec);
    socket_.set_option(boost::asio::socket_base::send_buffer_size(owner_.options().socket_send_buffer), ec);
    socket_.non_blocking(true, ec);  // read_available must never block
    auto self = shared_from_this();
    // The writer's completion handler holds the session alive until it ends; the server holds
    // it while it is open.
    boost::asio::co_spawn(socket_.get_executor(), writer(), [self](std::exception_ptr) {});
}

void session::read_available(std::span<uint8_t> buffer) {
    // What is there, without waiting: the server calls this once per tick for every session,
    // so one recv serves every input that arrived since the last tick (a client sends about one
    // per tick), and no socket is armed in epoll per read. Asio's async_wait re-armed the socket
    // with one epoll_ctl per input; the match consumes inputs only at ticks anyway.
    while (!closing_) {
        boost::system::error_code ec;
        const size_t n = socket_.read_some(boost::asio::buffer(buffer.data(), buffer.size()), ec);
        if (ec == boost::asio::error::would_block || ec == boost::asio::error::try_again) return;
        if (ec) {
            using kind = match::close_cause::kind;
            const bool eof = ec == boost::asio::error::eof;
            const kind what =
                !eof ? kind::socket_error : (reader_.buffered() > 0 ? kind::closed_mid_frame : kind::connection_closed);
            match_.disconnect(*this, {what, {}, eof ? std::string() : ec.message()});
            close_now();
            return;
        }
        owner_.count_in(n);
        // Rates are measured in real time: after a stall of the server, what queued is read at once.
        if (!take_frames(std::span<const uint8_t>(buffer.data(), n), owner_.now_ns())) return;
        if (n < buffer.size()) return;  // the socket is drained: the next recv would find nothing
    }
}

bool session::take_frames(std::span<const uint8_t> data, int64_t arrival_ns) {
    while (!closing_) {
        data = data.subspan(reader_.feed(data));
        if (reader_.failed()) {
            match_.reject(*this, match::admission::unreadable(reader_));
            return false;
        }
        if (!reader_.has_frame()) return true;  // the rest of the frame is still on its way
        auto verified = protocol::verify_message(reader_.frame(), protocol::client_frame_limits);
        if (!verified) {
            match_.reject(*this, match::admission::unverified(verified.error));
            return false;
        }
        owner_.count_message_in();
        const bool go_on = match_.receive(*this, *verified.value, arrival_ns);
        reader_.next();
        if (!go_on) {
            close_after({});  // a Bye from the client; after a refusal this changes nothing
            return false;
        }
    }
    return false;
}

boost::asio::awaitable<void> session::writer() {
    try {
        while (!closed_) {
            if (auto bytes = output_.next()) {
                if (!bytes->empty()) {
                    co_await boost::asio::async_write(socket_, boost::asio::buffer(bytes->data(), bytes->size()),
                                                      use_awaitable);
                    owner_.count_out(bytes->size());
                }
                output_.written(owner_.now_ns());
            } else if (closing_) {
                close_now();
                co_return;
            } else {
                wake_.expires_at(boost::asio::steady_timer::time_point::max());
                boost::system::error_code ec;
                co_await wake_.async_wait(boost::asio::redirect_error(use_awaitable, ec));
            }
        }
    } catch (const boost::system::system_error& e) {
        if (!closing_) match_.disconnect(*this, {match::close_cause::kind::write_failed, {}, e.code().message()});
        close_now();
    }
}

void session::send(protocol::frame_bytes frame) {
    if (closing_) return;
    if (!output_.push_control(std::move(frame), owner_.now_ns())) {
        // Not from inside the match's call that sent this: the refusal goes through the match.
        boost::asio::post(socket_.get_executor(), [self = shared_from_this()] {
            self->match_.reject(*self, {RejectCode::slow_consumer, "too many messages waiting to be sent"});
        });
        return;
    }
    wake_.cancel();
}

void session::send_snapshot(const protocol::snapshot_encoder& snapshot, uint32_t ack_sequence) {
    if (closing_) return;
    output_.put_snapshot(snapshot, ack_sequence, owner_.now_ns());
    wake_.cancel();
}

void session::send_snapshot_frame(std::span<const uint8_t> frame) {
    if (closing_) return;
    output_.put_snapshot_frame(frame, owner_.now_ns());
    wake_.cancel();
}

void session::close(RejectCode code, std::string_view reason) {
    close_after(protocol::encode_reject(code, reason));
}

void session::close_with_bye(std::string_view reason) {
    close_after(protocol::encode_bye(reason));
}

void session::close_with_result(std::string_view reason, const protocol::match_result& result) {
    close_after(protocol::encode_bye(reason, &result));
}

void session::close_after(protocol::frame_bytes last_frame) {
    if (closing_) return;
    closing_ = true;
    // Whatever was waiting is dropped: only the last word goes out, then the socket closes.
    output_.keep_only(std::move(last_frame));
    wake_.cancel();
    auto self = shared_from_this();
    linger_.expires_after(std::chrono::nanoseconds(owner_.options().close_grace_ns));
    linger_.async_wait([self](const boost::system::error_code& e) {
        if (!e) self->close_now();
    });
}

void session::close_now() {
    if (closed_) return;
    closed_ = true;
    closing_ = true;
    boost::system::error_code ec;
    socket_.shutdown(boost::asio::ip::tcp::socket::shutdown_both, ec);
    socket_.close(ec);
    wake_.cancel();
    linger_.cancel();
    owner_.on_gone(*this);
}

}  // namespace arena::net
