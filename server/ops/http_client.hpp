#pragma once
// One HTTP POST over a fresh loopback connection, bounded by a timeout: all the Agones sidecar
// needs. Connection: close, so the response ends where the stream ends.
#include <boost/asio.hpp>
#include <cstdint>
#include <string>

namespace arena::ops {

struct http_result {
    int status = 0;     // 0: no response (refused, reset, timed out, malformed)
    std::string error;  // why not, when status is 0
    bool ok() const { return status >= 200 && status < 300; }
};

boost::asio::awaitable<http_result> http_post(boost::asio::any_io_executor executor, std::string host, uint16_t port,
                                              std::string path, std::string json_body, int64_t timeout_ns);

}  // namespace arena::ops
