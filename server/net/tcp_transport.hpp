#pragma once
// The TCP transport: the game port (--port). Accepts clients into sessions (session.hpp), reads
// them all once per tick (read_before_tick: their sockets are out of the epoll set) and writes
// what the match queued after the handler that queued it (one flush for a tick's fan-out).
#include <array>
#include <boost/asio.hpp>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "server/host/transport.hpp"
#include "server/ops/accept_backoff.hpp"

namespace arena::net {

class session;

struct tcp_options {
    uint16_t port = 7777;  // 0: any free port
};

class tcp_transport final : public host::transport {
public:
    tcp_transport(host::transport_host& host, tcp_options options);
    ~tcp_transport() override;
    tcp_transport(const tcp_transport&) = delete;
    tcp_transport& operator=(const tcp_transport&) = delete;

    // Binds, listens, prints "listening on HOST:PORT", and accepts.
    void start() override;
    void stop() override;  // closes the listening socket
    void read_before_tick() override;
    void flush_after_tick() override;
    void check_stalls(int64_t now_ns) override;
    uint64_t open_connections() const override { return open_sessions_; }
    uint16_t port() const { return port_; }

    // For the sessions.
    host::transport_host& host() { return host_; }
    // The session's socket is closed: it is forgotten.
    void on_gone(session& s);
    // A session has output to write: flushed after the handler running now (one post for all
    // the sessions a tick or a read gave output), so a tick's sends do not lengthen the tick.
    void request_flush(std::shared_ptr<session> s);

private:
    boost::asio::awaitable<void> accept_loop();
    void flush_sessions();  // writes what request_flush() asked for
    // Before reading sessions_[i]: fetches into the cache what the next sessions' reads touch
    // first, while the kernel serves this one's recv (a read pass over 50 matches of 8 missed
    // the cache on each session, its client record and its player in turn).
    void fetch_ahead(size_t i) const;

    host::transport_host& host_;
    tcp_options options_;
    boost::asio::ip::tcp::acceptor acceptor_;
    ops::accept_backoff accept_backoff_;  // out of descriptors: pause accepting, log at a bounded rate
    uint16_t port_ = 0;
    bool stopped_ = false;
    // In accept order. A session closed while read_before_tick() runs leaves a null behind (its
    // reference moves to gone_ until the loop ends), removed after the loop.
    std::vector<std::shared_ptr<session>> sessions_;
    std::vector<std::shared_ptr<session>> gone_;
    bool reading_sessions_ = false;
    size_t open_sessions_ = 0;
    std::vector<std::shared_ptr<session>> to_flush_;  // request_flush()'s, for the next flush_sessions()
    std::vector<std::shared_ptr<session>> flushing_;  // flush_sessions()' copy: flushing may ask again
    bool flush_posted_ = false;
    // One for every session: one thread reads. 8-byte aligned, as a frame handed over in place
    // must be (protocol::frame_reader::whole_frame_at).
    alignas(8) std::array<uint8_t, 64 * 1024> read_buffer_{};
    uint64_t next_session_id_ = 1;
};

}  // namespace arena::net
