#pragma once
// One HTTP request over a fresh connection, bounded by a timeout: all the Agones sidecar and the
// container's health probe need. Connection: close, and only the response's status is read.
// HTTP is Boost.Beast's, kept inside http_client.cpp.
#include <boost/asio.hpp>
#include <cstdint>
#include <string>

namespace arena::ops {

struct http_result {
    int status = 0;     // 0: no response (refused, reset, timed out, malformed)
    std::string error;  // why not, when status is 0
    bool ok() const { return status >= 200 && status < 300; }
};

// POST with a JSON body (the Agones SDK's REST calls). host is an IP address.
boost::asio::awaitable<http_result> http_post(boost::asio::any_io_executor executor, std::string host, uint16_t port,
                                              std::string path, std::string json_body, int64_t timeout_ns);

// GET (arena-healthcheck). host is an IP address.
boost::asio::awaitable<http_result> http_get(boost::asio::any_io_executor executor, std::string host, uint16_t port,
                                             std::string path, int64_t timeout_ns);

}  // namespace arena::ops
