#include "client_sim/udp_bot.hpp"

#include <arpa/inet.h>
#include <unistd.h>

#include <cstring>

#include <boost/asio/co_spawn.hpp>
#include <boost/asio/detached.hpp>
#include <boost/asio/redirect_error.hpp>
#include <boost/asio/use_awaitable.hpp>

#include "client_sim/fleet.hpp"
#include "protocol/verify.hpp"

namespace arena::bots {

namespace {

using boost::asio::redirect_error;
using boost::asio::use_awaitable;
using end_kind = client_core::end_kind;

constexpr enet_uint8 channel_reliable = 0;
constexpr enet_uint8 channel_datagrams = 1;
// ENet's own resends and the delay lines are looked at this often while nothing else wakes us.
constexpr auto pump_interval = std::chrono::milliseconds(2);

// The payload of one of our own frames (we built it); Payload::NONE for bytes that are not a
// frame (the garbage fault), which go reliably like any control message.
protocol::Payload payload_of(std::span<const std::uint8_t> frame) {
    std::vector<std::uint64_t> aligned((frame.size() + 7) / 8);
    std::memcpy(aligned.data(), frame.data(), frame.size());
    auto verified = protocol::verify_message({reinterpret_cast<const std::uint8_t*>(aligned.data()), frame.size()},
                                             protocol::server_frame_limits);
    return verified ? verified.value->payload_type() : protocol::Payload::NONE;
}

}  // namespace

udp_bot::udp_bot(fleet& owner, client_params params, simulated_delay delay)
    : bot_session(owner,
                  [&] {
                      params.unordered = true;
                      return params;
                  }()),
      fleet_(owner),
      delay_(delay),
      jitter_rng_(params.seed * 0x9E3779B97F4A7C15ULL + params.index),
      readable_(owner.io()),
      timer_(owner.io()) {
    enet_initialize();
}

udp_bot::~udp_bot() {
    boost::system::error_code ignored;
    readable_.close(ignored);
    if (host_ != nullptr) enet_host_destroy(host_);
}

boost::asio::awaitable<void> udp_bot::run() {
    core_.launch(fleet_.now_ns());
    host_ = enet_host_create(nullptr, 1, 2, 0, 0);
    if (host_ == nullptr) {
        core_.on_transport_end(end_kind::transport_error, "cannot create a UDP socket");
        co_return;
    }
    ENetAddress address{};
    const auto endpoint = fleet_.endpoint();
    if (!endpoint.address().is_v4()) {
        core_.on_transport_end(end_kind::transport_error, "UDP (ENet) needs an IPv4 server address");
        co_return;
    }
    address.host = htonl(endpoint.address().to_v4().to_uint());
    address.port = endpoint.port();
    // A server with a token secret wants its current connect key in ENet's connect data.
    const auto& secret = fleet_.opts().token_secret;
    peer_ = enet_host_connect(host_, &address, 2, secret ? secret->connect_key(auth::unix_now()) : 0);
    const int fd = ::dup(host_->socket);
    if (peer_ == nullptr || fd < 0) {
        if (fd >= 0) ::close(fd);
        core_.on_transport_end(end_kind::transport_error, "cannot start an ENet connection");
        co_return;
    }
    readable_.assign(fd);
    enet_host_flush(host_);
    boost::asio::co_spawn(fleet_.io(), watch_socket(), boost::asio::detached);
    co_await pump();
}

boost::asio::awaitable<void> udp_bot::watch_socket() {
    boost::system::error_code ec;
    while (!closed_) {
        co_await readable_.async_wait(boost::asio::posix::stream_descriptor::wait_read,
                                      redirect_error(use_awaitable, ec));
        if (ec || closed_) co_return;
        service();
        sync();
    }
}

boost::asio::awaitable<void> udp_bot::pump() {
    boost::system::error_code ec;
    while (!closed_) {
        timer_.expires_after(pump_interval);
        co_await timer_.async_wait(redirect_error(use_awaitable, ec));
        if (closed_) co_return;
        service();
        sync();
    }
}

void udp_bot::service() {
    if (host_ == nullptr || closed_) return;
    ENetEvent event{};
    while (!closed_ && enet_host_service(host_, &event, 0) > 0) {
        switch (event.type) {
            case ENET_EVENT_TYPE_CONNECT:
                connected_ = true;
                core_.connected();
                break;
            case ENET_EVENT_TYPE_RECEIVE: {
                fleet_.count_in(event.packet->dataLength);
                std::vector<std::uint8_t> frame(event.packet->data, event.packet->data + event.packet->dataLength);
                enet_packet_destroy(event.packet);
                const time_ns now = fleet_.now_ns();
                if (delay_.latency_ms <= 0 && delay_.jitter_ms <= 0) {
                    core_.on_frame(frame, now);
                } else {
                    incoming_.emplace(now + delay_ns(true, last_in_), std::move(frame));
                }
                break;
            }
            case ENET_EVENT_TYPE_DISCONNECT:
                peer_ = nullptr;
                core_.on_transport_end(connected_ ? end_kind::by_server : end_kind::transport_error,
                                       connected_ ? "server closed the connection without Reject or Bye"
                                                  : "connect: no answer from the server");
                break;
            case ENET_EVENT_TYPE_NONE:
                break;
        }
    }
    deliver_due(fleet_.now_ns());
}

time_ns udp_bot::delay_ns(bool reliable, time_ns& last_reliable) {
    double ms = delay_.latency_ms;
    if (delay_.jitter_ms > 0) ms += (static_cast<double>(jitter_rng_.next_unit()) * 2 - 1) * delay_.jitter_ms;
    time_ns d = ms > 0 ? static_cast<time_ns>(ms * 1e6) : 0;
    if (reliable) {
        // In order behind the previous reliable message, as ENet delivers them.
        const time_ns now = fleet_.now_ns();
        if (now + d < last_reliable) d = last_reliable - now;
        last_reliable = now + d;
    }
    return d;
}

void udp_bot::deliver_due(time_ns now) {
    while (!incoming_.empty() && incoming_.begin()->first <= now && !core_.ended()) {
        std::vector<std::uint8_t> frame = std::move(incoming_.begin()->second);
        incoming_.erase(incoming_.begin());
        core_.on_frame(frame, now);
    }
    while (!outgoing_.empty() && outgoing_.begin()->first <= now && peer_ != nullptr) {
        send_now(outgoing_.begin()->second);
        outgoing_.erase(outgoing_.begin());
    }
    if (host_ != nullptr) enet_host_flush(host_);
}

void udp_bot::send_now(const delayed& d) {
    if (peer_ == nullptr) return;
    ENetPacket* packet = enet_packet_create(d.frame.data(), d.frame.size(),
                                            d.reliable ? ENET_PACKET_FLAG_RELIABLE : ENET_PACKET_FLAG_UNSEQUENCED);
    if (packet == nullptr) return;
    if (enet_peer_send(peer_, d.reliable ? channel_reliable : channel_datagrams, packet) != 0) {
        enet_packet_destroy(packet);
        return;
    }
    fleet_.count_out(d.frame.size());
}

void udp_bot::sync() {
    if (core_.ended()) {
        close_transport();
        return;
    }
    if (!connected_) return;
    std::vector<std::uint8_t>& queued = core_.output();
    // The core queues whole frames back to back: one message per ENet packet.
    std::span<const std::uint8_t> rest(queued);
    const time_ns now = fleet_.now_ns();
    const bool delayed_path = delay_.latency_ms > 0 || delay_.jitter_ms > 0;
    while (!rest.empty()) {
        std::size_t size = rest.size();
        if (rest.size() >= 4) {
            const std::uint32_t body =
                static_cast<std::uint32_t>(rest[0]) | (static_cast<std::uint32_t>(rest[1]) << 8) |
                (static_cast<std::uint32_t>(rest[2]) << 16) | (static_cast<std::uint32_t>(rest[3]) << 24);
            if (body <= rest.size() - 4) size = body + 4;
        }
        const auto frame = rest.first(size);
        rest = rest.subspan(size);
        const protocol::Payload type = payload_of(frame);
        // Inputs (and Pings, so that the round trip is the datagram's) are unreliable.
        delayed d{{frame.begin(), frame.end()}, type != protocol::Payload::Input && type != protocol::Payload::Ping};
        if (delayed_path)
            outgoing_.emplace(now + delay_ns(d.reliable, last_reliable_out_), std::move(d));
        else
            send_now(d);
    }
    queued.clear();
    if (host_ != nullptr) enet_host_flush(host_);
    if (core_.closing() && outgoing_.empty()) {
        core_.flushed();
        if (core_.ended()) close_transport();
    }
}

void udp_bot::close_transport() {
    if (closed_) return;
    closed_ = true;
    if (peer_ != nullptr && host_ != nullptr) {
        // What is queued (a Bye) goes out first; the server sees the disconnect, or times the
        // peer out if it is lost.
        enet_peer_disconnect_later(peer_, 0);
        enet_host_flush(host_);
    }
    boost::system::error_code ignored;
    readable_.cancel(ignored);
    timer_.cancel();
}

}  // namespace arena::bots
