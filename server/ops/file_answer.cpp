#include "server/ops/file_answer.hpp"

#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <cstdio>
#include <vector>

#include "server/ops/byte_range.hpp"

namespace arena::ops {

namespace beast = boost::beast;
namespace http = beast::http;

namespace {

auto use_ec(boost::system::error_code& ec) {
    return boost::asio::redirect_error(boost::asio::use_awaitable, ec);
}

struct file_closer {
    void operator()(std::FILE* f) const { std::fclose(f); }
};

http::response<http::empty_body> head_for(const file_request& request, http::status status) {
    http::response<http::empty_body> response{status, 11};
    response.set(http::field::server, "arena-server");
    response.set(http::field::content_type, request.content_type);
    response.set("X-Content-Type-Options", "nosniff");
    response.set(http::field::cache_control, "no-cache");
    response.set(http::field::accept_ranges, "bytes");
    if (request.any_origin) response.set(http::field::access_control_allow_origin, "*");
    response.keep_alive(false);  // Connection: close: one request per connection
    return response;
}

boost::asio::awaitable<boost::system::error_code> write_head(beast::tcp_stream& stream,
                                                             http::response<http::empty_body>& response) {
    boost::system::error_code ec;
    http::response_serializer<http::empty_body> serializer(response);
    co_await http::async_write_header(stream, serializer, use_ec(ec));
    co_return ec;
}

}  // namespace

int64_t steady_now_ns() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

int64_t file_pacer::reserve(int64_t now_ns, uint64_t bytes) {
    if (rate_ == 0) return 0;
    const int64_t burst_ns = 100'000'000;
    next_free_ns_ = std::max(next_free_ns_, now_ns - burst_ns);
    const int64_t start = next_free_ns_;
    next_free_ns_ += static_cast<int64_t>(static_cast<double>(bytes) * 1e9 / static_cast<double>(rate_));
    return std::max<int64_t>(0, start - now_ns);
}

double file_progress::rate(int64_t now_ns) const {
    const double elapsed_s = static_cast<double>(std::max<int64_t>(now_ns - started_ns, 1)) / 1e9;
    if (elapsed_s < 0.5) return 1e18;
    return static_cast<double>(sent) / elapsed_s;
}

boost::asio::awaitable<std::string> send_file(beast::tcp_stream& stream, const file_request& request,
                                              const file_send_limits& limits, std::shared_ptr<file_pacer> pacer,
                                              std::shared_ptr<file_progress> progress) {
    progress->started_ns = steady_now_ns();
    // One chunk's time for each write: the head (or a 404) is far smaller than a chunk.
    const auto chunk_deadline = std::chrono::nanoseconds(std::max<int64_t>(
        1'000'000'000, static_cast<int64_t>(static_cast<double>(limits.chunk_bytes) * 1e9 /
                                            static_cast<double>(std::max<uint64_t>(limits.min_bytes_per_second, 1)))));
    std::unique_ptr<std::FILE, file_closer> file(std::fopen(request.path.c_str(), "rb"));
    std::error_code size_ec;
    const uint64_t size = file ? std::filesystem::file_size(request.path, size_ec) : 0;
    stream.expires_after(chunk_deadline);
    if (!file || size_ec) {
        http::response<http::string_body> missing{http::status::not_found, 11};
        missing.set(http::field::content_type, "text/plain; charset=utf-8");
        missing.keep_alive(false);
        missing.body() = "not found\n";
        missing.prepare_payload();
        boost::system::error_code ec;
        co_await http::async_write(stream, missing, use_ec(ec));
        co_return "cannot open " + request.path.filename().string();
    }
    const byte_range range = parse_byte_range(request.range, size);
    if (range.what == byte_range::kind::unsatisfiable) {
        auto response = head_for(request, http::status::range_not_satisfiable);
        response.set(http::field::content_range, "bytes */" + std::to_string(size));
        response.content_length(0);
        const auto ec = co_await write_head(stream, response);
        co_return ec ? ec.message() : std::string();
    }
    const bool partial = range.what == byte_range::kind::partial;
    auto response = head_for(request, partial ? http::status::partial_content : http::status::ok);
    if (partial)
        response.set(http::field::content_range, "bytes " + std::to_string(range.first) + "-" +
                                                     std::to_string(range.first + range.length - 1) + "/" +
                                                     std::to_string(size));
    response.content_length(range.length);
    if (auto ec = co_await write_head(stream, response)) co_return ec.message();
    if (request.head_only) co_return std::string();
    if (range.first > 0 && ::fseeko(file.get(), static_cast<off_t>(range.first), SEEK_SET) != 0)
        co_return "cannot seek in " + request.path.filename().string();

    std::vector<uint8_t> chunk(limits.chunk_bytes);
    boost::asio::steady_timer pause(stream.get_executor());
    uint64_t left = range.length;
    while (left > 0) {
        const size_t want = static_cast<size_t>(std::min<uint64_t>(left, chunk.size()));
        if (const int64_t wait_ns = pacer->reserve(steady_now_ns(), want); wait_ns > 0) {
            boost::system::error_code ec;
            pause.expires_after(std::chrono::nanoseconds(wait_ns));
            co_await pause.async_wait(use_ec(ec));
            if (!stream.socket().is_open()) co_return "closed to make room";
        }
        // The file may have shrunk since its size was read: the answer ends short, the client sees it.
        const size_t n = std::fread(chunk.data(), 1, want, file.get());
        if (n == 0) co_return "the file ended before its size";
        boost::system::error_code ec;
        stream.expires_after(chunk_deadline);
        co_await boost::asio::async_write(stream, boost::asio::buffer(chunk.data(), n), use_ec(ec));
        if (ec == beast::error::timeout)
            co_return "slower than " + std::to_string(limits.min_bytes_per_second / 1024) + " KiB/s (" +
                std::to_string(progress->sent) + " of " + std::to_string(range.length) + " bytes sent)";
        if (ec) co_return ec.message();
        progress->sent += n;
        left -= n;
    }
    co_return std::string();
}

}  // namespace arena::ops
