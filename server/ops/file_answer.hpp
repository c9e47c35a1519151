#pragma once
// A file as an HTTP answer, in bounded chunks: the static files and /recording of the HTTP
// port (server/net/web_transport.cpp) and /recording of the metrics port (http_server.cpp).
// Both run on the game's io thread, so one answer never reads a large file at once: it reads
// `chunk_bytes`, writes them, and reads the next chunk only once they are sent; the chunks of
// every answer of one port share a byte rate (file_pacer), so that downloads cannot take the
// thread from the ticks. A chunk the client does not take within chunk / min_bytes_per_second
// ends the answer: a client that does not read holds its connection slot for seconds, not for
// the whole file. A single Range is honoured (206, or 416 when the file does not reach it).
// Included only by .cpp files that speak Beast (it is heavy to compile).
#include <boost/asio.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

namespace arena::ops {

// One port's budget for file bytes, shared by its answers: a leaky bucket that lets a chunk go
// at the earliest time the rate allows, with a burst of a tenth of a second's bytes.
class file_pacer {
public:
    explicit file_pacer(uint64_t bytes_per_second) : rate_(bytes_per_second) {}
    // How long (ns) to wait before `bytes` may be sent; reserves them.
    int64_t reserve(int64_t now_ns, uint64_t bytes);

private:
    uint64_t rate_;             // bytes per second; 0: unbounded
    int64_t next_free_ns_ = 0;  // when the bytes reserved so far have all gone at `rate_`
};

struct file_send_limits {
    size_t chunk_bytes = 64 * 1024;             // read from the file and written at a time (bytes)
    uint64_t min_bytes_per_second = 16 * 1024;  // each chunk within chunk / this (at least 1 s)
};

// An answer's progress, to find the slowest one when a slot is needed.
struct file_progress {
    uint64_t sent = 0;       // body bytes written so far
    int64_t started_ns = 0;  // steady clock, when the answer began
    // Bytes per second so far (a new answer counts as fast: it has not been given a chance).
    double rate(int64_t now_ns) const;
};

struct file_request {
    std::filesystem::path path;
    std::string content_type;
    std::string range;        // the request's Range header ("" when it has none)
    bool head_only = false;   // HEAD: the same headers, no body
    bool any_origin = false;  // Access-Control-Allow-Origin: * (a page on another port may read it)
};

// Writes the answer (200, 206, 416, or 404 when the file cannot be opened) and returns "" when it
// was all written, or why not (a line for the log). The stream's deadline is set per chunk.
// (request and limits are references: the caller keeps them, as named objects, until it is done;
// g++ 12 destroys a brace-initialised temporary argument of a coroutine twice.)
boost::asio::awaitable<std::string> send_file(boost::beast::tcp_stream& stream, const file_request& request,
                                              const file_send_limits& limits, std::shared_ptr<file_pacer> pacer,
                                              std::shared_ptr<file_progress> progress);

int64_t steady_now_ns();

}  // namespace arena::ops
