#include "server/net/session.hpp"

#include <sys/socket.h>
#include <sys/uio.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstring>
#include <ctime>
#include <system_error>

#include "server/host/log.hpp"
#include "server/net/tcp_transport.hpp"

namespace arena::net {

using protocol::RejectCode;

namespace {

std::string describe(const boost::asio::ip::tcp::socket& socket) {
    boost::system::error_code ec;
    const auto endpoint = socket.remote_endpoint(ec);
    if (ec) return "unknown-peer";
    return endpoint.address().to_string() + ":" + std::to_string(endpoint.port());
}

}  // namespace

session::session(boost::asio::ip::tcp::socket socket, tcp_transport& owner, uint64_t id)
    : owner_(owner),
      executor_(socket.get_executor()),
      accepted_(std::move(socket)),
      id_(id),
      peer_(describe(accepted_)),
      output_(owner.host().options().max_control_frames),
      linger_(executor_) {}

match::match& session::game() {
    return owner_.host().matches().match_of(*this);
}

session::~session() {
    if (room_) (void)room_->release();  // fd_ is closed below, once
    if (fd_ >= 0) ::close(fd_);
}

void session::start() {
    boost::system::error_code ec;
    accepted_.set_option(boost::asio::ip::tcp::no_delay(true), ec);
    accepted_.set_option(boost::asio::socket_base::send_buffer_size(owner_.host().options().socket_send_buffer), ec);
    // Out of the epoll set (one epoll_ctl): with it, every input that arrives would wake the
    // server, which reads only at ticks anyway. Every call below passes MSG_DONTWAIT.
    fd_ = accepted_.release(ec);
    if (ec) fd_ = -1;  // read_available reports the socket as failed
    // The kernel's receive time of the bytes each recv returns: a Ping waits here until the
    // tick's read, and its Pong tells the client how long (recv_timed).
    const int on = 1;
    if (fd_ >= 0) (void)::setsockopt(fd_, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof on);
}

namespace {

// recv with the kernel's receive time (SO_TIMESTAMPNS, CLOCK_REALTIME) of the newest bytes it
// returned: how long they waited before the read pass began (`wall_ns`, CLOCK_REALTIME), in ns;
// -1 when the kernel gave no time. Older bytes read with them waited longer, so for a Ping read
// beside later inputs this is a lower bound of its wait.
ssize_t recv_timed(int fd, std::span<uint8_t> buffer, int64_t wall_ns, int64_t& held_ns) {
    iovec io{buffer.data(), buffer.size()};
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(timespec))];
    msghdr msg{};
    msg.msg_iov = &io;
    msg.msg_iovlen = 1;
    msg.msg_control = control;
    msg.msg_controllen = sizeof control;
    const ssize_t n = ::recvmsg(fd, &msg, MSG_DONTWAIT);
    held_ns = -1;
    if (n <= 0) return n;
    for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
        if (c->cmsg_level != SOL_SOCKET || c->cmsg_type != SCM_TIMESTAMPNS) continue;
        timespec arrived{};
        std::memcpy(&arrived, CMSG_DATA(c), sizeof arrived);
        const int64_t waited = wall_ns - (static_cast<int64_t>(arrived.tv_sec) * 1'000'000'000 + arrived.tv_nsec);
        // Bytes that came during the pass, or a wall clock stepped back: no wait.
        held_ns = std::max<int64_t>(waited, 0);
    }
    return n;
}

// One system call's worth of `frames`: a lone frame (a tick's snapshot, most writes) by send,
// which spares the kernel copying in a message header and an iovec array; more by sendmsg.
ssize_t send_some(int fd, std::span<iovec> frames) {
    constexpr int flags = MSG_DONTWAIT | MSG_NOSIGNAL;
    if (frames.size() == 1) return ::send(fd, frames[0].iov_base, frames[0].iov_len, flags);
    msghdr message{};
    message.msg_iov = frames.data();
    message.msg_iovlen = std::min<size_t>(frames.size(), IOV_MAX);
    return ::sendmsg(fd, &message, flags);
}

}  // namespace

void session::read_available(std::span<uint8_t> buffer, int64_t now_ns, int64_t wall_ns) {
    // What is there, without waiting: the server calls this once per tick for every session,
    // so one recv serves every input that arrived since the last tick (a client sends about one
    // per tick). Waiting for readability cost an epoll_ctl per input (Asio re-arms the socket)
    // and a wake-up per input; the match consumes inputs only at ticks anyway.
    while (!closing_) {
        if (fd_ < 0) errno = EBADF;  // start() could not take the descriptor from Asio
        int64_t held_ns = -1;
        const ssize_t n = fd_ < 0 ? -1 : recv_timed(fd_, buffer, wall_ns, held_ns);
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return;
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            using kind = match::close_cause::kind;
            const bool eof = n == 0;
            const kind what =
                !eof ? kind::socket_error : (reader_.buffered() > 0 ? kind::closed_mid_frame : kind::connection_closed);
            game().disconnect(*this, {what, {}, eof ? std::string() : std::system_category().message(errno)});
            close_now();
            return;
        }
        const auto got = static_cast<size_t>(n);
        owner_.host().intake().count_bytes(got);
        // Rates are measured in real time: after a stall of the server, what queued is read at once.
        if (!take_frames(std::span<const uint8_t>(buffer.data(), got), now_ns, held_ns)) return;
        if (got < buffer.size()) return;  // the socket is drained: the next recv would find nothing
    }
}

bool session::take_frames(std::span<const uint8_t> data, int64_t arrival_ns, int64_t held_ns) {
    host::intake& intake = owner_.host().intake();
    while (!closing_) {
        // A whole frame where it lies, most reads' first: not copied into the reader.
        if (const auto whole = reader_.whole_frame_at(data); !whole.empty()) {
            data = data.subspan(whole.size());
            if (intake.take(*this, whole, arrival_ns, held_ns).go_on) continue;
            close_after({});  // as below
            return false;
        }
        data = data.subspan(reader_.feed(data));
        if (reader_.failed()) {
            intake.refuse_unreadable(*this, reader_);
            return false;
        }
        if (!reader_.has_frame()) return true;  // the rest of the frame is still on its way
        const bool go_on = intake.take(*this, reader_.frame(), arrival_ns, held_ns).go_on;
        reader_.next();
        if (!go_on) {
            close_after({});  // a Bye from the client; after a refusal this changes nothing
            return false;
        }
    }
    return false;
}

void session::request_flush() {
    if (flush_requested_ || waiting_for_room_ || closed_) return;
    flush_requested_ = true;
    owner_.request_flush(shared_from_this());
}

void session::flush() {
    flush_requested_ = false;
    if (closed_ || waiting_for_room_) return;
    write_pending();
}

void session::write_pending() {
    while (!closed_) {
        if (writing_from_ == writing_.size()) {
            const auto& batch = output_.take_all();
            if (batch.empty()) {
                if (closing_) half_close();  // the last word is out
                return;
            }
            writing_.clear();
            writing_from_ = 0;
            writing_bytes_ = 0;
            for (std::span<const uint8_t> frame : batch) {
                writing_.push_back({const_cast<uint8_t*>(frame.data()), frame.size()});
                writing_bytes_ += frame.size();
            }
            writing_frames_ = batch.size();
        }
        const ssize_t n = send_some(fd_, std::span<iovec>(writing_).subspan(writing_from_));
        if (n < 0 && errno == EINTR) continue;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
            wait_for_room();
            return;
        }
        if (n < 0) {
            if (!closing_)
                game().disconnect(*this,
                                  {match::close_cause::kind::write_failed, {}, std::system_category().message(errno)});
            close_now();
            return;
        }
        // Skip what went out; a frame cut in two goes on from where the kernel stopped.
        auto left = static_cast<size_t>(n);
        while (writing_from_ < writing_.size() && left >= writing_[writing_from_].iov_len)
            left -= writing_[writing_from_++].iov_len;
        if (writing_from_ < writing_.size()) {
            iovec& rest = writing_[writing_from_];
            rest.iov_base = static_cast<uint8_t*>(rest.iov_base) + left;
            rest.iov_len -= left;
            continue;
        }
        owner_.host().count_out(writing_bytes_, writing_frames_);
        output_.written(owner_.host().now_ns());
    }
}

void session::wait_for_room() {
    // The kernel's send buffer is full: fd_ joins the epoll set until it has room again.
    waiting_for_room_ = true;
    boost::system::error_code ec;
    room_.emplace(executor_);
    room_->assign(fd_, ec);
    if (ec) {
        (void)room_->release();
        room_.reset();
        waiting_for_room_ = false;
        if (!closing_) game().disconnect(*this, {match::close_cause::kind::write_failed, {}, ec.message()});
        close_now();
        return;
    }
    room_->async_wait(boost::asio::posix::stream_descriptor::wait_write,
                      [self = shared_from_this()](const boost::system::error_code& e) {
                          // Closed meanwhile (close_now released the descriptor): nothing to write.
                          if (e == boost::asio::error::operation_aborted || self->closed_) return;
                          self->waiting_for_room_ = false;
                          (void)self->room_->release();
                          self->room_.reset();
                          self->write_pending();  // an error shows in the write
                      });
}

void session::send(protocol::frame_bytes frame) {
    if (closing_) return;
    if (!output_.push_control(std::move(frame), owner_.host().now_ns())) {
        // Not from inside the match's call that sent this: the refusal goes through the match.
        boost::asio::post(executor_, [self = shared_from_this()] {
            self->game().reject(*self, {RejectCode::slow_consumer, "too many messages waiting to be sent"});
        });
        return;
    }
    request_flush();
}

void session::send_snapshot(const protocol::snapshot_encoder& snapshot, uint32_t ack_sequence) {
    if (closing_) return;
    output_.put_snapshot(snapshot, ack_sequence, owner_.host().now_ns());
    request_flush();
}

void session::send_snapshot_frame(std::span<const uint8_t> frame) {
    if (closing_) return;
    output_.put_snapshot_frame(frame, owner_.host().now_ns());
    request_flush();
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
    request_flush();
    auto self = shared_from_this();
    linger_.expires_after(std::chrono::nanoseconds(owner_.host().options().close_grace_ns));
    linger_.async_wait([self](const boost::system::error_code& e) {
        if (!e) self->close_now();
    });
}

void session::half_close() {
    // Closing with inputs still unread would make the kernel answer with a reset: the client's
    // next write fails, and a client that writes before it reads ends on that error and never
    // sees the Bye (or Reject) already in its socket. So our side ends after the last word (a
    // FIN), and what the client still sends is read and dropped until its own end arrives.
    if (fd_ < 0 || ::shutdown(fd_, SHUT_WR) != 0) return close_now();
    drain_until_closed();
}

void session::drain_until_closed() {
    // A few reads a wake-up, so that a client flooding its half-closed connection takes no
    // more of the loop than a reading one; linger_ bounds the whole wait.
    uint8_t scrap[16384];
    for (int reads = 0; reads < 8; ++reads) {
        const ssize_t n = ::recv(fd_, scrap, sizeof scrap, MSG_DONTWAIT);
        if (n > 0) {
            owner_.host().intake().count_bytes(static_cast<size_t>(n));
            continue;
        }
        if (n < 0 && errno == EINTR) continue;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) break;
        return close_now();  // the client's end (or an error): nothing more will come
    }
    boost::system::error_code ec;
    room_.emplace(executor_);
    room_->assign(fd_, ec);
    if (ec) return close_now();
    room_->async_wait(boost::asio::posix::stream_descriptor::wait_read,
                      [self = shared_from_this()](const boost::system::error_code& e) {
                          if (e == boost::asio::error::operation_aborted || self->closed_) return;
                          (void)self->room_->release();
                          self->room_.reset();
                          self->drain_until_closed();
                      });
}

void session::close_now() {
    if (closed_) return;
    closed_ = true;
    closing_ = true;
    if (room_) {
        (void)room_->release();  // leaves the epoll set; the wait ends as aborted
        room_.reset();
    }
    if (fd_ >= 0) {
        ::shutdown(fd_, SHUT_RDWR);
        ::close(fd_);
        fd_ = -1;
    }
    linger_.cancel();
    owner_.on_gone(*this);
}

}  // namespace arena::net
