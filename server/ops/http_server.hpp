#pragma once
// The ops HTTP endpoint: GET /metrics and GET /healthz on their own port (and, with
// --serve-recording, /recording), one request per connection. Small on purpose: it answers
// Prometheus, the kubelet, Docker's HEALTHCHECK and an operator's curl, never players, so it
// bounds what a stray client can cost (request size, read time, open connections) and nothing
// more. HTTP itself is Boost.Beast's; Beast stays inside http_server.cpp and file_answer.cpp (it
// is heavy to compile).
#include <boost/asio.hpp>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "server/ops/accept_backoff.hpp"
#include "server/ops/http_routes.hpp"

namespace arena::ops {

struct http_server_options {
    std::string bind = "127.0.0.1";
    uint16_t port = 0;                              // 0: any free port (see port())
    size_t max_request_bytes = 8 * 1024;            // request line + headers; more gets 431
    int64_t read_timeout_ns = 5'000'000'000;        // the whole head must arrive within this
    int64_t first_byte_timeout_ns = 1'000'000'000;  // and its first byte within this
    // At this many open connections, a new one closes the oldest that is still sending its head
    // (an idle or slow client) to take its place; when every one is being answered, it is closed.
    uint32_t max_connections = 32;
    // --serve-recording: the --record file at /recording (empty: a 404), in chunks
    // (file_answer.hpp), readable by a page of any origin (the replay page on --http-port).
    std::filesystem::path recording;
    uint64_t file_bytes_per_second = 32 << 20;  // /recording's bytes, on the game's thread
};

class http_server {
public:
    // log: where accept errors go (rate-limited); may be empty.
    http_server(boost::asio::io_context& io, http_server_options options, http_handlers handlers,
                std::function<void(const std::string&)> log = {});
    ~http_server();

    // Binds and listens (throws boost::system::system_error when it cannot), then accepts in the
    // background on the io_context.
    void start();
    // Stops accepting; connections being answered finish on their own. Idempotent.
    void stop();
    uint16_t port() const { return port_; }

    // Connections counted, and connections closed to make room for newer ones, since start.
    uint32_t open_connections() const;
    uint64_t evicted_connections() const;
    // Failed accepts since start (each paused the loop when it was for want of descriptors).
    uint64_t accept_errors() const { return accept_backoff_.errors(); }

    // Shared with the connection coroutines, so that one still running after the server is
    // gone finds `alive` false instead of a dangling pointer. Defined in http_server.cpp.
    struct shared_state;

private:
    boost::asio::awaitable<void> accept_loop();

    boost::asio::io_context& io_;
    http_server_options options_;
    http_handlers handlers_;
    boost::asio::ip::tcp::acceptor acceptor_;
    uint16_t port_ = 0;
    accept_backoff accept_backoff_;
    std::shared_ptr<shared_state> state_;
};

}  // namespace arena::ops
