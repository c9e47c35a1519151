#include "server/ops/http_server.hpp"

#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <cctype>
#include <chrono>
#include <list>
#include <optional>

#include "server/ops/file_answer.hpp"

namespace arena::ops {

namespace beast = boost::beast;
namespace http = beast::http;
using boost::asio::ip::tcp;

// One connection: its stream, and its place in the queue of those still sending their head.
struct http_connection {
    explicit http_connection(tcp::socket socket) : stream(std::move(socket)) {}
    beast::tcp_stream stream;
    std::list<std::shared_ptr<http_connection>>::iterator waiting_at;
    bool waiting = false;  // in shared_state::waiting
    bool counted = true;   // in shared_state::open (an evicted connection no longer is)
};

struct http_server::shared_state {
    explicit shared_state(uint64_t file_rate) : pacer(std::make_shared<file_pacer>(file_rate)) {}
    bool alive = true;
    std::shared_ptr<file_pacer> pacer;  // /recording's byte rate
    uint32_t open = 0;
    uint64_t evicted = 0;
    // Connections still sending their request head, oldest first: the ones a new connection may
    // replace when all slots are taken, so that 32 idle sockets cannot keep a health probe out.
    std::list<std::shared_ptr<http_connection>> waiting;

    void stop_waiting(http_connection& c) {
        if (!c.waiting) return;
        waiting.erase(c.waiting_at);
        c.waiting = false;
    }
    void uncount(http_connection& c) {
        if (!c.counted) return;
        --open;
        c.counted = false;
    }
    // Closes the oldest connection still sending its head; false when there is none.
    bool evict_oldest() {
        if (waiting.empty()) return false;
        const auto oldest = waiting.front();
        stop_waiting(*oldest);
        uncount(*oldest);
        ++evicted;
        oldest->stream.close();  // its read ends with operation_aborted: nothing to answer
        return true;
    }
};

namespace {

auto use_ec(boost::system::error_code& ec) {
    return boost::asio::redirect_error(boost::asio::use_awaitable, ec);
}

// A refusal to answer with: status and a one-line reason for the body.
struct http_error {
    int status;
    std::string reason;
};

// What reading a request head ends in: a request, an error to answer, or nothing to answer
// (the peer went away, or the deadline passed: neither is waiting for a reply).
struct read_result {
    std::optional<http_request> request;
    std::optional<http_error> error;
};

// Beast parses only CRLF line endings: a request with bare LF ones ("GET / HTTP/1.1\n\n", as
// typed into nc) got a vague 400 or, when Beast waited for a CRLF CRLF that never came, silence
// until the deadline. Such a head is refused at once, with the reason. Only the head is looked
// at (up to the first CRLF CRLF): a body may hold any bytes.
bool has_bare_lf(const beast::flat_buffer& buffer) {
    const std::string_view text(static_cast<const char*>(buffer.data().data()), buffer.size());
    const std::string_view head = text.substr(0, text.find("\r\n\r\n"));
    for (size_t i = 0; i < head.size(); ++i)
        if (head[i] == '\n' && (i == 0 || head[i - 1] != '\r')) return true;
    return false;
}

// Beast refuses any version but 1.0 and 1.1 as malformed; a well-formed other version ("HTTP/2.0")
// deserves 505, which says what the client can do about it.
http_error version_error(const beast::flat_buffer& buffer) {
    const std::string_view text(static_cast<const char*>(buffer.data().data()), buffer.size());
    const std::string_view line = text.substr(0, text.find("\r\n"));
    const bool well_formed = line.size() > 9 && line.substr(line.size() - 9, 6) == " HTTP/" &&
                             std::isdigit(static_cast<unsigned char>(line[line.size() - 3])) &&
                             line[line.size() - 2] == '.' &&
                             std::isdigit(static_cast<unsigned char>(line[line.size() - 1]));
    if (well_formed) return {505, "only HTTP/1.0 and HTTP/1.1"};
    return {400, "bad version"};
}

// Beast's parser does the parsing (HTTP/1.0 and 1.1 only); this adds the rules it leaves to us:
// an upper-case method, an origin-form target.
read_result check_head(const http::request_parser<http::empty_body>& parser) {
    const auto& head = parser.get();
    const auto method = head.method_string();
    for (char c : method)
        if (c < 'A' || c > 'Z') return {{}, http_error{400, "malformed method"}};
    const auto target = head.target();
    if (target.empty() || target.front() != '/') return {{}, http_error{400, "malformed target"}};
    const auto path = target.substr(0, target.find('?'));
    return {http_request{std::string(method), std::string(path)}, {}};
}

// Reads one request head of at most `limit` bytes, feeding Beast's parser as bytes arrive.
// Deadlines: the first byte within first_byte_timeout_ns (an idle socket goes soon), the whole
// head within read_timeout_ns of the connection's start.
// range: set to the request's Range header (for /recording).
boost::asio::awaitable<read_result> read_head(beast::tcp_stream& stream, const http_server_options& options,
                                              std::string& range) {
    const size_t limit = options.max_request_bytes;
    const auto started = std::chrono::steady_clock::now();
    stream.expires_after(std::chrono::nanoseconds(std::min(options.first_byte_timeout_ns, options.read_timeout_ns)));
    http::request_parser<http::empty_body> parser;
    parser.header_limit(static_cast<uint32_t>(limit));
    beast::flat_buffer buffer(limit);
    for (;;) {
        boost::system::error_code ec;
        const size_t room = std::min<size_t>(buffer.max_size() - buffer.size(), 2048);
        const size_t n = co_await stream.async_read_some(buffer.prepare(room), use_ec(ec));
        if (ec) co_return read_result{};
        if (buffer.size() == 0) stream.expires_at(started + std::chrono::nanoseconds(options.read_timeout_ns));
        buffer.commit(n);
        if (has_bare_lf(buffer))
            co_return read_result{{}, http_error{400, "bare LF line ending: HTTP lines end in CRLF"}};
        buffer.consume(parser.put(buffer.data(), ec));
        if (!ec && parser.is_header_done()) {
            range = std::string(parser.get()[http::field::range]);
            co_return check_head(parser);
        }
        if (ec == http::error::header_limit || (ec == http::error::need_more && buffer.size() >= limit))
            co_return read_result{{}, http_error{431, "request head larger than " + std::to_string(limit) + " bytes"}};
        if (ec == http::error::bad_version) co_return read_result{{}, version_error(buffer)};
        if (ec && ec != http::error::need_more) co_return read_result{{}, http_error{400, ec.message()}};
    }
}

http_response plain(int status, std::string body) {
    return {status, "text/plain; charset=utf-8", std::move(body)};
}

http::response<http::string_body> to_beast(const http_response& r) {
    http::response<http::string_body> response{static_cast<http::status>(r.status), 11};
    response.set(http::field::content_type, r.content_type);
    if (r.status == 405) response.set(http::field::allow, "GET, HEAD");
    response.set(http::field::cache_control, "no-store");
    response.keep_alive(false);  // Connection: close: one request per connection
    response.body() = r.body;
    response.prepare_payload();
    return response;
}

boost::asio::awaitable<void> serve(std::shared_ptr<http_server::shared_state> state, http_handlers handlers,
                                   http_server_options options, std::shared_ptr<http_connection> conn) {
    ++state->open;
    conn->waiting_at = state->waiting.insert(state->waiting.end(), conn);
    conn->waiting = true;
    std::string range;
    const read_result head = co_await read_head(conn->stream, options, range);
    state->stop_waiting(*conn);

    boost::system::error_code ec;
    const bool head_only = head.request && head.request->method == "HEAD";
    if (head.request && head.request->path == "/recording" && !options.recording.empty() && state->alive &&
        (head_only || head.request->method == "GET")) {
        // Every body's position: served here, on the private address, only with --serve-recording.
        const file_request file{options.recording, "application/octet-stream", range, head_only, true};
        const file_send_limits limits;
        const auto progress = std::make_shared<file_progress>();
        co_await send_file(conn->stream, file, limits, state->pacer, progress);
        conn->stream.socket().shutdown(tcp::socket::shutdown_send, ec);
        conn->stream.socket().close(ec);
        state->uncount(*conn);
        co_return;
    }
    std::optional<http_response> reply;
    if (head.request)
        reply = state->alive ? route(*head.request, handlers) : plain(503, "shutting down\n");
    else if (head.error)
        reply = plain(head.error->status, head.error->reason + "\n");
    // Otherwise the peer went away, the deadline passed or a newer connection took the slot:
    // nothing to answer.
    if (reply) {
        conn->stream.expires_after(std::chrono::nanoseconds(options.read_timeout_ns));
        auto response = to_beast(*reply);
        if (head_only) {
            // HEAD: GET's headers (its Content-Length too), no body.
            http::response_serializer<http::string_body> serializer(response);
            co_await http::async_write_header(conn->stream, serializer, use_ec(ec));
        } else {
            co_await http::async_write(conn->stream, response, use_ec(ec));
        }
        conn->stream.socket().shutdown(tcp::socket::shutdown_send, ec);
    }
    conn->stream.socket().close(ec);
    state->uncount(*conn);
}

}  // namespace

http_server::http_server(boost::asio::io_context& io, http_server_options options, http_handlers handlers,
                         std::function<void(const std::string&)> log)
    : io_(io),
      options_(std::move(options)),
      handlers_(std::move(handlers)),
      acceptor_(io),
      accept_backoff_("metrics", std::move(log)),
      state_(std::make_shared<shared_state>(options_.file_bytes_per_second)) {}

uint32_t http_server::open_connections() const {
    return state_->open;
}

uint64_t http_server::evicted_connections() const {
    return state_->evicted;
}

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
        tcp::socket socket = co_await acceptor_.async_accept(use_ec(ec));
        if (!state->alive || ec == boost::asio::error::operation_aborted || !acceptor_.is_open()) co_return;
        if (ec) {
            // Out of descriptors, the queued connection stays and accept fails again at once:
            // pause rather than spin, and log at a bounded rate.
            co_await accept_backoff_.pause_after(ec);
            if (!state->alive || !acceptor_.is_open()) co_return;  // `this` may be gone
            continue;
        }
        accept_backoff_.succeeded();
        // Full: the oldest connection still sending its head makes room; when every slot is
        // being answered, the new socket closes as it goes out of scope.
        if (state->open >= options_.max_connections && !state->evict_oldest()) continue;
        // Copies: the server may be destroyed while this connection is still being answered.
        boost::asio::co_spawn(io_,
                              serve(state, handlers_, options_, std::make_shared<http_connection>(std::move(socket))),
                              boost::asio::detached);
    }
}

}  // namespace arena::ops
