#include "server/ops/http_client.hpp"

#include <chrono>
#include <memory>

#include "server/ops/http_message.hpp"

namespace arena::ops {

using boost::asio::ip::tcp;

namespace {

constexpr size_t max_response_bytes = 16 * 1024;  // a response head; the sidecar sends a few lines

struct exchange {
    explicit exchange(boost::asio::any_io_executor ex) : socket(ex), timer(ex) {}
    tcp::socket socket;
    boost::asio::steady_timer timer;
    bool timed_out = false;
};

}  // namespace

boost::asio::awaitable<http_result> http_post(boost::asio::any_io_executor executor, std::string host, uint16_t port,
                                              std::string path, std::string json_body, int64_t timeout_ns) {
    // The timer's handler shares ownership, so firing late never touches a freed socket.
    auto x = std::make_shared<exchange>(executor);
    x->timer.expires_after(std::chrono::nanoseconds(timeout_ns));
    x->timer.async_wait([x](const boost::system::error_code& ec) {
        if (ec) return;
        x->timed_out = true;
        boost::system::error_code ignored;
        x->socket.close(ignored);
    });

    boost::system::error_code ec;
    const auto address = boost::asio::ip::make_address(host, ec);
    if (ec) {
        x->timer.cancel();
        co_return http_result{0, "bad address " + host};
    }
    co_await x->socket.async_connect(tcp::endpoint(address, port),
                                     boost::asio::redirect_error(boost::asio::use_awaitable, ec));
    if (!ec) {
        const std::string request = format_post(host, port, path, json_body);
        co_await boost::asio::async_write(x->socket, boost::asio::buffer(request),
                                          boost::asio::redirect_error(boost::asio::use_awaitable, ec));
    }
    std::string response;
    if (!ec) {
        // Only the status line matters, so the head is enough: no waiting for the body or for
        // a sidecar that keeps the connection open despite "Connection: close".
        co_await boost::asio::async_read_until(x->socket, boost::asio::dynamic_buffer(response, max_response_bytes),
                                               "\r\n\r\n", boost::asio::redirect_error(boost::asio::use_awaitable, ec));
    }
    x->timer.cancel();
    boost::system::error_code ignored;
    x->socket.close(ignored);
    if (x->timed_out) co_return http_result{0, "timed out"};
    if (ec) co_return http_result{0, ec.message()};
    const int status = parse_response_status(response);
    co_return http_result{status, status == 0 ? "malformed response" : ""};
}

}  // namespace arena::ops
