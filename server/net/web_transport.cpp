#include "server/net/web_transport.hpp"

#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <cstdio>

#include "server/host/log.hpp"
#include "server/net/ws_session.hpp"

namespace arena::net {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using boost::asio::ip::tcp;

// One HTTP connection until it is answered or becomes a WebSocket.
struct http_conn {
    explicit http_conn(tcp::socket socket) : stream(std::move(socket)) {}
    beast::tcp_stream stream;
    std::list<std::shared_ptr<http_conn>>::iterator waiting_at;
    bool waiting = false;  // in web_transport::waiting_ (still sending its head)
    bool counted = false;  // in web_transport::http_open_
};

namespace {

auto use_ec(boost::system::error_code& ec) {
    return boost::asio::redirect_error(boost::asio::use_awaitable, ec);
}

std::string describe(const tcp::socket& socket) {
    boost::system::error_code ec;
    const auto endpoint = socket.remote_endpoint(ec);
    if (ec) return "unknown-peer";
    return endpoint.address().to_string() + ":" + std::to_string(endpoint.port());
}

double seconds(int64_t ns) {
    return static_cast<double>(ns) / 1e9;
}

template <class Body>
void common_headers(http::response<Body>& response, std::string_view content_type) {
    response.set(http::field::server, "arena-server");
    response.set(http::field::content_type, content_type);
    response.set("X-Content-Type-Options", "nosniff");
    response.keep_alive(false);  // Connection: close: one request per connection
}

http::response<http::string_body> text_response(int status, std::string_view content_type, std::string body) {
    http::response<http::string_body> response{static_cast<http::status>(status), 11};
    common_headers(response, content_type);
    response.set(http::field::cache_control, "no-store");
    if (status == 405) response.set(http::field::allow, "GET, HEAD");
    response.body() = std::move(body);
    response.prepare_payload();
    return response;
}

bool origin_allowed(const std::vector<std::string>& allowed, std::string_view origin) {
    if (allowed.empty()) return true;
    for (const std::string& a : allowed)
        if (beast::iequals(a, origin)) return true;
    return false;
}

}  // namespace

web_transport::web_transport(host::transport_host& host, web_options options, ops::http_handlers handlers)
    : io_(host.io()),
      host_(host),
      options_(std::move(options)),
      handlers_(std::move(handlers)),
      files_(options_.web_root),
      acceptor_(host.io()),
      accept_backoff_("http", [](const std::string& line) { host::log_line("%s", line.c_str()); }),
      watchdog_(host.io()),
      alive_(std::make_shared<bool>(true)) {}

web_transport::~web_transport() {
    *alive_ = false;
    boost::system::error_code ec;
    acceptor_.close(ec);
    watchdog_.cancel();
    for (auto& c : waiting_) c->stream.socket().close(ec);
}

void web_transport::start() {
    const tcp::endpoint endpoint(boost::asio::ip::make_address(host_.options().bind), options_.port);
    acceptor_.open(endpoint.protocol());
    acceptor_.set_option(tcp::acceptor::reuse_address(true));
    acceptor_.bind(endpoint);
    acceptor_.listen(boost::asio::socket_base::max_listen_connections);
    port_ = acceptor_.local_endpoint().port();
    std::printf("http listening on %s:%u\n", host_.options().bind.c_str(), port_);
    std::fflush(stdout);
    const std::string root = files_.serving() ? files_.root().string() : std::string("(none)");
    host::log_line("http: /ws, /metrics, /healthz and files from %s on %s:%u; origins: %s", root.c_str(),
                   host_.options().bind.c_str(), port_,
                   options_.allowed_origins.empty() ? "any" : std::to_string(options_.allowed_origins.size()).c_str());
    boost::asio::co_spawn(io_, accept_loop(), boost::asio::detached);
    watch_stalls();
}

void web_transport::watch_stalls() {
    watchdog_.expires_after(std::chrono::milliseconds(250));
    watchdog_.async_wait([this, alive = alive_](const boost::system::error_code& ec) {
        if (ec || !*alive) return;
        // Like the TCP sessions': output that has not moved for the stall timeout drops the client.
        const int64_t now = host_.now_ns();
        std::vector<std::shared_ptr<ws_session>> stalled;
        for (auto& [id, s] : sessions_)
            if (!s->closing() && s->stalled_ns(now) > host_.options().stall_timeout_ns) stalled.push_back(s);
        for (auto& s : stalled)
            host_.matches().match_of(*s).reject(
                *s, {protocol::RejectCode::slow_consumer, "no progress writing to the client"});
        watch_stalls();
    });
}

void web_transport::on_open(const std::shared_ptr<ws_session>& s) {
    sessions_.emplace(s->id(), s);
    host_.connection_opened();
}

void web_transport::on_gone(ws_session& s) {
    if (sessions_.erase(s.id()) > 0) host_.connection_closed();
}

void web_transport::forget_http(http_conn& c) {
    if (c.waiting) {
        waiting_.erase(c.waiting_at);
        c.waiting = false;
    }
    if (c.counted) {
        --http_open_;
        c.counted = false;
    }
}

bool web_transport::evict_oldest_waiting() {
    if (waiting_.empty()) return false;
    const auto oldest = waiting_.front();
    forget_http(*oldest);
    ++evicted_;
    boost::system::error_code ec;
    oldest->stream.socket().close(ec);  // its read ends with operation_aborted: nothing to answer
    return true;
}

boost::asio::awaitable<void> web_transport::accept_loop() {
    const auto alive = alive_;
    for (;;) {
        boost::system::error_code ec;
        tcp::socket socket = co_await acceptor_.async_accept(use_ec(ec));
        if (!*alive || ec == boost::asio::error::operation_aborted || !acceptor_.is_open()) co_return;
        if (ec) {
            co_await accept_backoff_.pause_after(ec);
            if (!*alive || !acceptor_.is_open()) co_return;
            continue;
        }
        accept_backoff_.succeeded();
        // Full: the oldest connection still sending its head makes room; when every one is being
        // answered, the new socket closes as it goes out of scope.
        if (http_open_ >= options_.max_http_connections && !evict_oldest_waiting()) continue;
        auto conn = std::make_shared<http_conn>(std::move(socket));
        ++http_open_;
        conn->counted = true;
        conn->waiting_at = waiting_.insert(waiting_.end(), conn);
        conn->waiting = true;
        boost::asio::co_spawn(io_, serve(std::move(conn)), boost::asio::detached);
    }
}

boost::asio::awaitable<void> web_transport::serve(std::shared_ptr<http_conn> conn) {
    const auto alive = alive_;
    const std::string peer = describe(conn->stream.socket());
    const host::host_options& game = host_.options();
    // The whole head within the handshake timeout: an upgrade that never completes holds a
    // slot no longer than a TCP client that never says Hello.
    conn->stream.expires_after(std::chrono::nanoseconds(game.handshake_timeout_ns));
    http::request_parser<http::empty_body> parser;
    parser.header_limit(static_cast<uint32_t>(options_.max_request_bytes));
    parser.body_limit(0);  // GET has no body
    beast::flat_buffer buffer(options_.max_request_bytes);
    boost::system::error_code ec;
    co_await http::async_read(conn->stream, buffer, parser, use_ec(ec));
    if (!*alive) co_return;
    const bool evicted = !conn->counted;
    if (conn->waiting) {
        waiting_.erase(conn->waiting_at);
        conn->waiting = false;
    }
    if (evicted) co_return;  // a newer connection took the slot

    std::optional<http::response<http::string_body>> reply;
    if (ec) {
        const bool said_nothing = buffer.size() == 0 && !parser.got_some();
        if (ec == beast::error::timeout) {
            host::log_line("http: %s: request head not complete within %.1f s", peer.c_str(),
                           seconds(game.handshake_timeout_ns));
        } else if (ec == http::error::header_limit || ec == http::error::buffer_overflow) {
            host::log_line("http: %s: request head larger than %zu bytes", peer.c_str(), options_.max_request_bytes);
            reply =
                text_response(431, "text/plain; charset=utf-8",
                              "request head larger than " + std::to_string(options_.max_request_bytes) + " bytes\n");
        } else if (ec == http::error::end_of_stream || ec == boost::asio::error::eof ||
                   ec == boost::asio::error::connection_reset) {
            if (!said_nothing) host::log_line("http: %s: closed inside its request head", peer.c_str());
        } else {
            host::log_line("http: %s: bad request: %s", peer.c_str(), ec.message().c_str());
            reply = text_response(400, "text/plain; charset=utf-8", ec.message() + "\n");
        }
    } else {
        http::request<http::empty_body> request = parser.release();
        const std::string_view target = request.target();
        const std::string path(target.substr(0, target.find('?')));
        if (path == "/ws") {
            const std::string_view origin = request[http::field::origin];
            if (!websocket::is_upgrade(request)) {
                reply = text_response(426, "text/plain; charset=utf-8", "/ws is a WebSocket endpoint\n");
                reply->set(http::field::upgrade, "websocket");
            } else if (!origin_allowed(options_.allowed_origins, origin)) {
                host::log_line("ws: %s: upgrade refused: Origin '%.*s' is not allowed (--allowed-origin)", peer.c_str(),
                               static_cast<int>(std::min<size_t>(origin.size(), 200)), origin.data());
                reply = text_response(403, "text/plain; charset=utf-8", "origin not allowed\n");
            } else if (host_.shutting_down()) {
                reply = text_response(503, "text/plain; charset=utf-8", "shutting down\n");
            } else {
                // From here the match bounds it (with TCP's connections): no longer an HTTP slot.
                forget_http(*conn);
                auto session = std::make_shared<ws_session>(std::move(conn->stream), *this, next_session_id(), peer);
                co_await session->run(std::move(request));
                co_return;
            }
        } else if (path == "/metrics" || path == "/healthz") {
            const ops::http_response r = ops::route({std::string(request.method_string()), path}, handlers_);
            reply = text_response(r.status, r.content_type, r.body);
            if (r.status == 405) reply->set(http::field::allow, "GET");
        } else if (request.method() != http::verb::get && request.method() != http::verb::head) {
            reply = text_response(405, "text/plain; charset=utf-8", "only GET and HEAD\n");
        } else {
            static_refusal why;
            std::optional<static_file> file;
            // The session's recording as far as the recorder has flushed it (once a second):
            // a replay plays it up to its last complete tick. Written like any static file.
            const bool recording = path == "/recording";
            if (recording && !options_.recording.empty())
                file = static_file{options_.recording, "application/octet-stream"};
            else if (!recording)
                file = files_.resolve(path, &why);
            if (recording && !file) {
                reply = text_response(404, "text/plain; charset=utf-8",
                                      "not found: the server records no session (--record)\n");
            } else if (!file) {
                if (why.hostile)
                    host::log_line("http: %s: refused path '%.*s': %s", peer.c_str(),
                                   static_cast<int>(std::min<size_t>(path.size(), 200)), path.data(),
                                   why.reason.c_str());
                reply = text_response(why.status, "text/plain; charset=utf-8",
                                      why.status == 404 ? "not found\n" : why.reason + "\n");
            } else {
                http::response<http::file_body> response{http::status::ok, 11};
                common_headers(response, file->content_type);
                response.set(http::field::cache_control, "no-cache");
                response.body().open(file->path.c_str(), beast::file_mode::scan, ec);
                if (ec) {
                    reply = text_response(404, "text/plain; charset=utf-8", "not found\n");
                } else {
                    response.prepare_payload();
                    conn->stream.expires_after(std::chrono::nanoseconds(options_.write_timeout_ns));
                    if (request.method() == http::verb::head) {
                        http::response_serializer<http::file_body> serializer(response);
                        co_await http::async_write_header(conn->stream, serializer, use_ec(ec));
                    } else {
                        co_await http::async_write(conn->stream, response, use_ec(ec));
                    }
                    if (!*alive) co_return;
                }
            }
        }
    }
    if (reply) {
        conn->stream.expires_after(std::chrono::nanoseconds(options_.write_timeout_ns));
        co_await http::async_write(conn->stream, *reply, use_ec(ec));
        if (!*alive) co_return;
    }
    conn->stream.socket().shutdown(tcp::socket::shutdown_send, ec);
    conn->stream.socket().close(ec);
    forget_http(*conn);
}

}  // namespace arena::net
