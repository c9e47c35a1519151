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

auto use_ec(boost::system::error_code& ec) {
    return boost::asio::redirect_error(boost::asio::use_awaitable, ec);
}

http_result failure(const boost::system::error_code& ec) {
    if (ec == beast::error::timeout) return http_result{0, "timed out"};
    return http_result{0, ec.message()};
}

// Connects `stream` and sends the request; ec says whether it went.
boost::asio::awaitable<void> send_request(beast::tcp_stream& stream, http::verb method, const std::string& host,
                                          uint16_t port, const std::string& path, std::string body,
                                          boost::system::error_code& ec) {
    const auto address = boost::asio::ip::make_address(host, ec);
    if (ec) co_return;
    co_await stream.async_connect(tcp::endpoint(address, port), use_ec(ec));
    if (ec) co_return;
    http::request<http::string_body> request{method, path, 11};
    request.set(http::field::host, host + ":" + std::to_string(port));
    if (!body.empty() || method == http::verb::post) request.set(http::field::content_type, "application/json");
    request.keep_alive(false);
    request.body() = std::move(body);
    request.prepare_payload();
    co_await http::async_write(stream, request, use_ec(ec));
}

boost::asio::awaitable<http_result> exchange(boost::asio::any_io_executor executor, http::verb method,
                                             const std::string& host, uint16_t port, const std::string& path,
                                             std::string body, int64_t timeout_ns, bool read_body) {
    boost::system::error_code ec;
    if (boost::asio::ip::make_address(host, ec); ec) co_return http_result{0, "bad address " + host};

    // One deadline for the whole exchange: connect, request, response head (and body).
    beast::tcp_stream stream(executor);
    stream.expires_after(std::chrono::nanoseconds(timeout_ns));
    co_await send_request(stream, method, host, port, path, std::move(body), ec);
    http_result result;
    beast::flat_buffer buffer;
    if (read_body) {
        http::response_parser<http::string_body> parser;
        parser.header_limit(max_response_head_bytes);
        parser.body_limit(max_response_body_bytes);
        if (!ec) co_await http::async_read(stream, buffer, parser, use_ec(ec));
        if (!ec) result = http_result{static_cast<int>(parser.get().result_int()), "", std::move(parser.get().body())};
    } else {
        // Only the status matters, so the head is enough: no waiting for the body or for a
        // server that keeps the connection open despite "Connection: close".
        http::response_parser<http::empty_body> parser;
        parser.header_limit(max_response_head_bytes);
        if (!ec) co_await http::async_read_header(stream, buffer, parser, use_ec(ec));
        if (!ec) result = http_result{static_cast<int>(parser.get().result_int()), ""};
    }
    boost::system::error_code ignored;
    stream.socket().close(ignored);
    if (ec) co_return failure(ec);
    co_return result;
}

}  // namespace

boost::asio::awaitable<http_result> http_post(boost::asio::any_io_executor executor, std::string host, uint16_t port,
                                              std::string path, std::string json_body, int64_t timeout_ns) {
    co_return co_await exchange(std::move(executor), http::verb::post, host, port, path, std::move(json_body),
                                timeout_ns, false);
}

boost::asio::awaitable<http_result> http_get(boost::asio::any_io_executor executor, std::string host, uint16_t port,
                                             std::string path, int64_t timeout_ns) {
    co_return co_await exchange(std::move(executor), http::verb::get, host, port, path, "", timeout_ns, false);
}

boost::asio::awaitable<http_result> http_call(boost::asio::any_io_executor executor, std::string method,
                                              std::string host, uint16_t port, std::string path, std::string json_body,
                                              int64_t timeout_ns) {
    const http::verb verb = http::string_to_verb(method);
    if (verb == http::verb::unknown) co_return http_result{0, "bad method " + method};
    co_return co_await exchange(std::move(executor), verb, host, port, path, std::move(json_body), timeout_ns, true);
}

struct http_line_stream::connection {
    explicit connection(boost::asio::any_io_executor executor) : stream(std::move(executor)) {}
    beast::tcp_stream stream;
};

http_line_stream::http_line_stream(boost::asio::any_io_executor executor)
    : connection_(std::make_shared<connection>(std::move(executor))) {}

http_line_stream::~http_line_stream() {
    close();
}

void http_line_stream::close() {
    boost::system::error_code ignored;
    connection_->stream.socket().shutdown(tcp::socket::shutdown_both, ignored);
    connection_->stream.cancel();
    connection_->stream.socket().close(ignored);
}

boost::asio::awaitable<http_result> http_line_stream::run(std::string host, uint16_t port, std::string path,
                                                          int64_t timeout_ns,
                                                          std::function<void(std::string_view)> on_line) {
    // Held by the coroutine too: close() from the destructor must not free the socket under it.
    const std::shared_ptr<connection> keep = connection_;
    beast::tcp_stream& stream = keep->stream;
    boost::system::error_code ec;
    if (boost::asio::ip::make_address(host, ec); ec) co_return http_result{0, "bad address " + host};
    stream.expires_after(std::chrono::nanoseconds(timeout_ns));
    co_await send_request(stream, http::verb::get, host, port, path, "", ec);
    beast::flat_buffer buffer;
    http::response_parser<http::string_body> parser;
    parser.header_limit(max_response_head_bytes);
    parser.body_limit(boost::none);  // bounded below, line by line
    if (!ec) co_await http::async_read_header(stream, buffer, parser, use_ec(ec));
    if (ec) co_return failure(ec);
    const int status = static_cast<int>(parser.get().result_int());
    if (status < 200 || status >= 300) co_return http_result{status, ""};
    stream.expires_never();
    // The parser appends what arrives to the body (chunked or not); whole lines are taken
    // from its front, so the body holds at most one partial line.
    std::string& body = parser.get().body();
    while (!parser.is_done()) {
        co_await http::async_read_some(stream, buffer, parser, use_ec(ec));
        if (ec) break;
        size_t start = 0;
        for (size_t end; (end = body.find('\n', start)) != std::string::npos; start = end + 1) {
            std::string_view line(body.data() + start, end - start);
            if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
            if (!line.empty()) on_line(line);
        }
        body.erase(0, start);
        if (body.size() > max_line_bytes) co_return http_result{status, "a line longer than 1 MiB"};
    }
    if (ec == http::error::end_of_stream || ec == http::error::partial_message) co_return http_result{status, "ended"};
    if (ec) co_return http_result{status, ec.message()};
    co_return http_result{status, "ended"};
}

}  // namespace arena::ops
