#include "server/ops/http_server.hpp"

#include <chrono>

namespace arena::ops {

using boost::asio::ip::tcp;

namespace {

// A socket with a deadline: when the timer fires the socket closes, which ends any read in
// progress. Both live in one shared object that the timer's handler keeps alive, so a late
// handler never touches a socket that is gone.
struct timed_socket {
    explicit timed_socket(tcp::socket s) : socket(std::move(s)), timer(socket.get_executor()) {}
    tcp::socket socket;
    boost::asio::steady_timer timer;
};

void arm_deadline(const std::shared_ptr<timed_socket>& conn, int64_t timeout_ns) {
    conn->timer.expires_after(std::chrono::nanoseconds(timeout_ns));
    conn->timer.async_wait([conn](const boost::system::error_code& ec) {
        if (!ec) {
            boost::system::error_code ignored;
            conn->socket.close(ignored);
        }
    });
}

}  // namespace

http_server::http_server(boost::asio::io_context& io, http_server_options options, http_handlers handlers)
    : io_(io), options_(std::move(options)), handlers_(std::move(handlers)), acceptor_(io) {}

http_server::~http_server() {
    state_->alive = false;
    stop();
}

void http_server::start() {
    const tcp::endpoint endpoint(boost::asio::ip::make_address(options_.bind), options_.port);
    acceptor_.open(endpoint.protocol());
    acceptor_.set_option(tcp::acceptor::reuse_address(true));
    acceptor_.bind(endpoint);
    acceptor_.listen();
    port_ = acceptor_.local_endpoint().port();
    boost::asio::co_spawn(io_, accept_loop(), boost::asio::detached);
}

void http_server::stop() {
    boost::system::error_code ignored;
    acceptor_.close(ignored);
}

boost::asio::awaitable<void> http_server::accept_loop() {
    const auto state = state_;
    for (;;) {
        boost::system::error_code ec;
        tcp::socket socket =
            co_await acceptor_.async_accept(boost::asio::redirect_error(boost::asio::use_awaitable, ec));
        if (!state->alive || ec == boost::asio::error::operation_aborted || !acceptor_.is_open()) co_return;
        if (ec) continue;                                       // e.g. EMFILE: the next accept may succeed
        if (state->open >= options_.max_connections) continue;  // the socket closes as it goes
        boost::asio::co_spawn(io_, serve(std::move(socket)), boost::asio::detached);
    }
}

boost::asio::awaitable<void> http_server::serve(tcp::socket socket) {
    const auto state = state_;
    ++state->open;
    // Copies: the server may be destroyed while this connection is still being answered.
    const http_handlers handlers = handlers_;
    const size_t limit = options_.max_request_bytes;
    auto conn = std::make_shared<timed_socket>(std::move(socket));
    arm_deadline(conn, options_.read_timeout_ns);

    std::string head;
    boost::system::error_code ec;
    const size_t n =
        co_await boost::asio::async_read_until(conn->socket, boost::asio::dynamic_buffer(head, limit), "\r\n\r\n",
                                               boost::asio::redirect_error(boost::asio::use_awaitable, ec));
    std::string reply;
    if (!ec) {
        auto parsed = parse_request_head(std::string_view(head).substr(0, n));
        if (auto* request = std::get_if<http_request>(&parsed))
            reply = state->alive ? format_response(route(*request, handlers)) : format_error({503, "shutting down"});
        else
            reply = format_error(std::get<http_error>(parsed));
    } else if (ec == boost::asio::error::not_found) {
        // async_read_until stops at the buffer's max_size without finding the blank line.
        reply = format_error({431, "request head larger than " + std::to_string(limit) + " bytes"});
    }
    // Otherwise the peer went away or the deadline closed the socket: nothing to answer.
    if (!reply.empty() && conn->socket.is_open()) {
        co_await boost::asio::async_write(conn->socket, boost::asio::buffer(reply),
                                          boost::asio::redirect_error(boost::asio::use_awaitable, ec));
        conn->socket.shutdown(tcp::socket::shutdown_send, ec);
    }
    conn->timer.cancel();
    conn->socket.close(ec);
    --state->open;
}

}  // namespace arena::ops
