#pragma once
// One HTTP request over a fresh connection, bounded by a timeout: all the Agones sidecar and the
// container's health probe need. Connection: close. http_post and http_get read only the
// response's status; http_call reads the body too (the sidecar's Counters and Lists answer
// with JSON), and http_line_stream reads a response that never ends, line by line (the
// sidecar's /watch/gameserver). HTTP is Boost.Beast's, kept inside http_client.cpp.
#include <boost/asio.hpp>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

namespace arena::ops {

struct http_result {
    int status = 0;      // 0: no response (refused, reset, timed out, malformed)
    std::string error;   // why not, when status is 0
    std::string body{};  // http_call only: the response's body (at most max_response_body_bytes)
    bool ok() const { return status >= 200 && status < 300; }
};

inline constexpr uint32_t max_response_body_bytes = 256 * 1024;  // a sidecar's answer is a few lines

// POST with a JSON body (the Agones SDK's REST calls). host is an IP address.
boost::asio::awaitable<http_result> http_post(boost::asio::any_io_executor executor, std::string host, uint16_t port,
                                              std::string path, std::string json_body, int64_t timeout_ns);

// GET (arena-healthcheck). host is an IP address.
boost::asio::awaitable<http_result> http_get(boost::asio::any_io_executor executor, std::string host, uint16_t port,
                                             std::string path, int64_t timeout_ns);

// Any method ("GET", "POST", "PATCH", ...), a JSON body when not empty, and the response's body
// read whole. host is an IP address; timeout_ns bounds the whole exchange.
boost::asio::awaitable<http_result> http_call(boost::asio::any_io_executor executor, std::string method,
                                              std::string host, uint16_t port, std::string path, std::string json_body,
                                              int64_t timeout_ns);

// A GET whose response body is a stream of lines (one JSON object each), handed to `on_line`
// as they arrive, without their line ends. run() returns when the server ends the stream, the
// connection fails, or close() is called; connecting and the response head are bounded by
// timeout_ns, the stream itself is not (an event may come hours later).
class http_line_stream {
public:
    explicit http_line_stream(boost::asio::any_io_executor executor);
    ~http_line_stream();
    http_line_stream(const http_line_stream&) = delete;
    http_line_stream& operator=(const http_line_stream&) = delete;

    // status is the response's (an answer other than 2xx ends the stream at once).
    boost::asio::awaitable<http_result> run(std::string host, uint16_t port, std::string path, int64_t timeout_ns,
                                            std::function<void(std::string_view line)> on_line);
    // Ends a run() in progress (it returns with an error); safe to call when none is.
    void close();

    static constexpr size_t max_line_bytes = 1024 * 1024;  // a GameServer is a few KiB

private:
    struct connection;
    std::shared_ptr<connection> connection_;
};

}  // namespace arena::ops
