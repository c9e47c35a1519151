#include "server/net/tcp_transport.hpp"

#include <algorithm>
#include <cstdio>
#include <ctime>

#include "server/host/log.hpp"
#include "server/net/session.hpp"

namespace arena::net {

using boost::asio::use_awaitable;
using boost::asio::ip::tcp;

tcp_transport::tcp_transport(host::transport_host& host, tcp_options options)
    : host_(host),
      options_(options),
      acceptor_(host.io()),
      accept_backoff_("game", [](const std::string& line) { host::log_line("%s", line.c_str()); }) {}

tcp_transport::~tcp_transport() = default;

void tcp_transport::start() {
    const std::string& bind = host_.options().bind;
    const tcp::endpoint endpoint(boost::asio::ip::make_address(bind), options_.port);
    acceptor_.open(endpoint.protocol());
    acceptor_.set_option(tcp::acceptor::reuse_address(true));
    acceptor_.bind(endpoint);
    acceptor_.listen(boost::asio::socket_base::max_listen_connections);
    port_ = acceptor_.local_endpoint().port();
    std::printf("listening on %s:%u\n", bind.c_str(), port_);
    std::fflush(stdout);
    boost::asio::co_spawn(host_.io(), accept_loop(), boost::asio::detached);
}

void tcp_transport::stop() {
    stopped_ = true;
    boost::system::error_code ec;
    acceptor_.close(ec);
}

boost::asio::awaitable<void> tcp_transport::accept_loop() {
    while (!stopped_) {
        boost::system::error_code ec;
        tcp::socket socket = co_await acceptor_.async_accept(boost::asio::redirect_error(use_awaitable, ec));
        if (ec) {
            if (stopped_ || ec == boost::asio::error::operation_aborted) co_return;
            // Out of descriptors the connection stays queued and accept fails again at once:
            // retrying at once spun a core and logged millions of lines. Pause instead.
            co_await accept_backoff_.pause_after(ec);
            if (stopped_) co_return;
            continue;
        }
        accept_backoff_.succeeded();
        auto s = std::make_shared<session>(std::move(socket), *this, next_session_id_++);
        sessions_.push_back(s);
        ++open_sessions_;
        host_.connection_opened();
        s->start();
        host_.matches().match_of(*s).connect(*s);  // after start(), so that a refused client reads why
    }
}

void tcp_transport::read_before_tick() {
    // By index: a session that closes while it reads leaves a null (on_gone), and none is added.
    // One clock reading for the pass: it takes a millisecond or two, far finer than the rates
    // it times, and a reading per recv was a cost of its own.
    reading_sessions_ = true;
    const int64_t now = host_.now_ns();
    timespec wall{};
    ::clock_gettime(CLOCK_REALTIME, &wall);  // the kernel's receive times are on this clock
    const int64_t wall_ns = static_cast<int64_t>(wall.tv_sec) * 1'000'000'000 + wall.tv_nsec;
    for (size_t i = 0; i < sessions_.size(); ++i) {
        fetch_ahead(i);
        if (session* s = sessions_[i].get()) s->read_available(read_buffer_, now, wall_ns);
    }
    reading_sessions_ = false;
    if (!gone_.empty()) {
        std::erase(sessions_, nullptr);
        gone_.clear();
    }
}

void tcp_transport::fetch_ahead(size_t i) const {
    // Each stage needs the one before it in the cache: the session three ahead, the match's
    // record of the one two ahead (fetched a stage ago), the player of the next one, and the
    // slot of this one's input ring that its Input will be written to once the kernel has
    // served its recv. Sessions, records and players keep what a read and an Input touch in
    // their first two cache lines (session.hpp, match.hpp).
    const auto at = [&](size_t k) {
        return k < sessions_.size() ? sessions_[k].get() : nullptr;
    };
    const auto fetch_two_lines = [](const void* p) {
        __builtin_prefetch(p);
        __builtin_prefetch(static_cast<const char*>(p) + 64);
    };
    if (const session* s = at(i + 3)) fetch_two_lines(s);
    if (const session* s = at(i + 2); s && s->record) fetch_two_lines(s->record);
    if (const session* s = at(i + 1); s && s->record && s->record->player) fetch_two_lines(s->record->player);
    if (const session* s = at(i); s && s->record && s->record->player)
        __builtin_prefetch(s->record->player->inputs.next_slot(), 1);
}

void tcp_transport::request_flush(std::shared_ptr<session> s) {
    to_flush_.push_back(std::move(s));
    if (flush_posted_) return;
    flush_posted_ = true;
    boost::asio::post(host_.io(), [this] { flush_sessions(); });
}

void tcp_transport::flush_after_tick() {
    flush_sessions();  // the posted flush that the tick's sends asked for then finds nothing
}

void tcp_transport::flush_sessions() {
    flush_posted_ = false;
    flushing_.swap(to_flush_);
    for (auto& s : flushing_) s->flush();
    flushing_.clear();
}

void tcp_transport::check_stalls(int64_t now) {
    std::vector<std::shared_ptr<session>> stalled;
    for (auto& s : sessions_)
        if (s && !s->closing() && s->stalled_ns(now) > host_.options().stall_timeout_ns) stalled.push_back(s);
    for (auto& s : stalled)
        host_.matches().match_of(*s).reject(*s,
                                            {protocol::RejectCode::slow_consumer, "no progress writing to the client"});
}

void tcp_transport::on_gone(session& s) {
    const auto it = std::find_if(sessions_.begin(), sessions_.end(), [&](const auto& p) { return p.get() == &s; });
    if (it == sessions_.end()) return;
    --open_sessions_;
    if (reading_sessions_)
        gone_.push_back(std::move(*it));  // alive until read_before_tick() ends: it may be reading
    else
        sessions_.erase(it);
    host_.connection_closed();
}

}  // namespace arena::net
