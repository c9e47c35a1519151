#include "server/ops/http_client.hpp"

#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <chrono>

namespace arena::ops {

namespace beast = boost::beast;
namespace http = beast::http;
using boost::asio::ip::tcp;

namespace {

constexpr uint32_t max_response_head_bytes = 16 * 1024;  // the sidecar sends a few lines

boost::asio::awaitable<http_result> exchange(boost::asio::any_io_executor executor, http::verb method,
                                             const std::string& host, uint16_t port, const std::string& path,
                                             std::string body, int64_t timeout_ns) {
    boost::system::error_code ec;
    const auto address = boost::asio::ip::make_address(host, ec);
    if (ec) co_return http_result{0, "bad address " + host};

    // One deadline for the whole exchange: connect, request, response head.
    beast::tcp_stream stream(executor);
    stream.expires_after(std::chrono::nanoseconds(timeout_ns));
    auto use_ec = [&ec] {
        return boost::asio::redirect_error(boost::asio::use_awaitable, ec);
    };
    co_await stream.async_connect(tcp::endpoint(address, port), use_ec());
    if (!ec) {
        http::request<http::string_body> request{method, path, 11};
        request.set(http::field::host, host + ":" + std::to_string(port));
        if (method == http::verb::post) request.set(http::field::content_type, "application/json");
        request.keep_alive(false);
        request.body() = std::move(body);
        request.prepare_payload();
        co_await http::async_write(stream, request, use_ec());
    }
    // Only the status matters, so the head is enough: no waiting for the body or for a server
    // that keeps the connection open despite "Connection: close".
    http::response_parser<http::empty_body> parser;
    parser.header_limit(max_response_head_bytes);
    if (!ec) {
        beast::flat_buffer buffer;
        co_await http::async_read_header(stream, buffer, parser, use_ec());
    }
    boost::system::error_code ignored;
    stream.socket().close(ignored);
    if (ec == beast::error::timeout) co_return http_result{0, "timed out"};
    if (ec) co_return http_result{0, ec.message()};
    co_return http_result{static_cast<int>(parser.get().result_int()), ""};
}

}  // namespace

boost::asio::awaitable<http_result> http_post(boost::asio::any_io_executor executor, std::string host, uint16_t port,
                                              std::string path, std::string json_body, int64_t timeout_ns) {
    co_return co_await exchange(std::move(executor), http::verb::post, host, port, path, std::move(json_body),
                                timeout_ns);
}

boost::asio::awaitable<http_result> http_get(boost::asio::any_io_executor executor, std::string host, uint16_t port,
                                             std::string path, int64_t timeout_ns) {
    co_return co_await exchange(std::move(executor), http::verb::get, host, port, path, "", timeout_ns);
}

}  // namespace arena::ops
