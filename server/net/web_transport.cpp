#include "server/net/web_transport.hpp"

#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <cstdio>
#include <sstream>

#include "server/host/log.hpp"
#include "server/net/upgrade_checks.hpp"
#include "server/net/ws_session.hpp"
#include "server/ops/file_answer.hpp"

namespace arena::net {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using boost::asio::ip::tcp;

// One HTTP connection until it is answered or becomes a WebSocket.
struct http_conn {
    explicit http_conn(tcp::socket socket) : stream(std::move(socket)) {}
    beast::tcp_stream stream;
    http::request<http::empty_body> request;  // once its head is read
    std::string body;                         // a lobby POST's (the only request with one)
    std::list<std::shared_ptr<http_conn>>::iterator waiting_at;
    std::list<std::shared_ptr<http_conn>>::iterator download_at;
    std::shared_ptr<ops::file_progress> progress = std::make_shared<ops::file_progress>();
    bool waiting = false;      // in web_transport::waiting_ (still sending its head)
    bool downloading = false;  // in web_transport::downloads_ (writing a file)
    bool counted = false;      // in web_transport::http_open_
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

// The answer to HEAD is GET's without its body (a load balancer's probe).
boost::asio::awaitable<boost::system::error_code> write_reply(beast::tcp_stream& stream,
                                                              http::response<http::string_body>& reply,
                                                              bool head_only) {
    boost::system::error_code ec;
    if (head_only) {
        http::response_serializer<http::string_body> serializer(reply);
        co_await http::async_write_header(stream, serializer, use_ec(ec));
    } else {
        co_await http::async_write(stream, reply, use_ec(ec));
    }
    co_return ec;
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
      alive_(std::make_shared<bool>(true)),
      pacer_(std::make_shared<ops::file_pacer>(options_.file_bytes_per_second)) {}

web_transport::~web_transport() {
    *alive_ = false;
    boost::system::error_code ec;
    acceptor_.close(ec);
    watchdog_.cancel();
    for (auto& c : waiting_) c->stream.socket().close(ec);
    for (auto& c : downloads_) c->stream.socket().close(ec);
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
    host::log_line(
        "http: /ws, %s/healthz and files from %s on %s:%u; origins: %s", options_.serve_metrics ? "/metrics, " : "",
        root.c_str(), host_.options().bind.c_str(), port_,
        options_.allowed_origins.empty() ? "the page's own" : std::to_string(options_.allowed_origins.size()).c_str());
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
    if (c.downloading) {
        downloads_.erase(c.download_at);
        c.downloading = false;
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

bool web_transport::evict_slowest_download() {
    if (downloads_.empty()) return false;
    const int64_t now = ops::steady_now_ns();
    auto slowest = downloads_.front();
    for (const auto& d : downloads_)
        if (d->progress->rate(now) < slowest->progress->rate(now)) slowest = d;
    forget_http(*slowest);
    ++evicted_;
    boost::system::error_code ec;
    slowest->stream.socket().close(ec);  // its write ends with operation_aborted
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
        // Full: the oldest connection still sending its head makes room, else the slowest
        // download; when every one is a small answer being written, the new socket closes as it
        // goes out of scope.
        if (http_open_ >= options_.max_http_connections && !evict_oldest_waiting() && !evict_slowest_download())
            continue;
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
    conn->stream.expires_after(game.match.admission.handshake_timeout);
    http::request_parser<http::empty_body> parser;
    parser.header_limit(static_cast<uint32_t>(options_.max_request_bytes));
    // A body is read only for a lobby POST (below); a larger one is refused with the head.
    parser.body_limit(host::max_lobby_body_bytes);
    beast::flat_buffer buffer(options_.max_request_bytes);
    boost::system::error_code ec;
    // The head only: a request that announces a body (chunked, or a Content-Length) is refused
    // at once below, instead of waiting for a body until the deadline.
    co_await http::async_read_header(conn->stream, buffer, parser, use_ec(ec));
    if (!*alive) co_return;
    const bool evicted = !conn->counted;
    if (conn->waiting) {
        waiting_.erase(conn->waiting_at);
        conn->waiting = false;
    }
    if (evicted) co_return;  // a newer connection took the slot

    std::optional<http::response<http::string_body>> reply;
    // A lobby POST may carry a small body (POST /matches: {"mode": ...}); it is read whole
    // within the same deadline, up to host::max_lobby_body_bytes.
    if (!ec && !parser.is_done() && parser.get().method() == http::verb::post &&
        host::is_lobby_path(std::string_view(parser.get().target()).substr(0, parser.get().target().find('?'))) &&
        parser.content_length() && *parser.content_length() <= host::max_lobby_body_bytes) {
        http::request_parser<http::string_body> with_body(std::move(parser));
        with_body.body_limit(host::max_lobby_body_bytes);
        co_await http::async_read(conn->stream, buffer, with_body, use_ec(ec));
        if (!*alive) co_return;
        if (!ec) {
            conn->body = std::move(with_body.get().body());
            conn->request = http::request<http::empty_body>(std::move(with_body.get().base()));
            co_await answer(conn, peer, {});
            co_return;
        }
    } else if (!ec && !parser.is_done()) {
        host::log_line("http: %s: refused a request with a body (Transfer-Encoding or Content-Length)", peer.c_str());
        reply = text_response(400, "text/plain; charset=utf-8", "a request body is not accepted\n");
    } else if (ec) {
        const bool said_nothing = buffer.size() == 0 && !parser.got_some();
        if (ec == beast::error::timeout) {
            host::log_line("http: %s: request head not complete within %.1f s", peer.c_str(),
                           std::chrono::duration<double>(game.match.admission.handshake_timeout).count());
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
        conn->request = parser.release();
        // Bytes after the head (a WebSocket frame sent with the upgrade) belong to the session.
        const auto* data = static_cast<const uint8_t*>(buffer.data().data());
        std::vector<uint8_t> leftover(data, data + buffer.size());
        co_await answer(conn, peer, std::move(leftover));
        co_return;
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

bool web_transport::origin_allowed(std::string_view origin, std::string_view host) const {
    return net::origin_allowed(options_.allowed_origins, origin, host);
}

boost::asio::awaitable<void> web_transport::answer(std::shared_ptr<http_conn> conn, const std::string& peer,
                                                   std::vector<uint8_t> leftover) {
    const auto alive = alive_;
    const http::request<http::empty_body>& request = conn->request;
    const std::string_view target = request.target();
    const std::string path(target.substr(0, target.find('?')));
    const bool head_only = request.method() == http::verb::head;
    std::optional<http::response<http::string_body>> reply;
    boost::system::error_code ec;
    if (path == "/ws") {
        const std::string_view origin = request[http::field::origin];
        if (!websocket::is_upgrade(request)) {
            reply = text_response(426, "text/plain; charset=utf-8", "/ws is a WebSocket endpoint\n");
            reply->set(http::field::upgrade, "websocket");
        } else if (!valid_websocket_key(request[http::field::sec_websocket_key])) {
            host::log_line("ws: %s: upgrade refused: Sec-WebSocket-Key is not the base64 of 16 bytes", peer.c_str());
            reply =
                text_response(400, "text/plain; charset=utf-8", "Sec-WebSocket-Key must be the base64 of 16 bytes\n");
        } else if (!origin_allowed(origin, request[http::field::host])) {
            host::log_line(
                "ws: %s: upgrade refused: Origin '%.*s' is not allowed (%s)", peer.c_str(),
                static_cast<int>(std::min<size_t>(origin.size(), 200)), origin.data(),
                options_.allowed_origins.empty() ? "not this page's; see --allowed-origin" : "--allowed-origin");
            reply = text_response(403, "text/plain; charset=utf-8", "origin not allowed\n");
        } else if (host_.shutting_down()) {
            reply = text_response(503, "text/plain; charset=utf-8", "shutting down\n");
        } else {
            // From here the match bounds it (with TCP's connections): no longer an HTTP slot.
            forget_http(*conn);
            auto session = std::make_shared<ws_session>(std::move(conn->stream), *this, next_session_id(), peer);
            co_await session->run(std::move(conn->request), std::move(leftover));
            co_return;
        }
    } else if (host::is_lobby_path(path)) {
        boost::system::error_code address_ec;
        const auto remote = conn->stream.socket().remote_endpoint(address_ec);
        const host::lobby_answer a = host_.lobby({std::string(request.method_string()), path, std::move(conn->body),
                                                  address_ec ? peer : remote.address().to_string(),
                                                  std::string(request[http::field::authorization])});
        reply = text_response(a.status, a.content_type, a.body);
        if (a.status == 405) reply->set(http::field::allow, path == "/matches" ? "GET, HEAD, POST" : "GET, HEAD");
    } else if ((path == "/metrics" && options_.serve_metrics) || path == "/healthz") {
        const ops::http_response r = ops::route({std::string(request.method_string()), path}, handlers_);
        reply = text_response(r.status, r.content_type, r.body);
        if (r.status == 405) reply->set(http::field::allow, "GET, HEAD");
    } else if (request.method() != http::verb::get && !head_only) {
        reply = text_response(405, "text/plain; charset=utf-8", "only GET and HEAD\n");
    } else if (path == "/recording") {
        // Every body's position at every tick: a map of the whole match. Served only when
        // asked for, and here only once the match is over (while it runs, on the metrics port).
        if (options_.recording.empty() || !options_.serve_recording) {
            reply = text_response(404, "text/plain; charset=utf-8",
                                  options_.recording.empty()
                                      ? "not found: the server records no session (--record)\n"
                                      : "not found: the recording is not served (see --serve-recording)\n");
        } else if (!host_.shutting_down()) {
            reply = text_response(404, "text/plain; charset=utf-8",
                                  "not found: while the match runs, the recording is served on the metrics port "
                                  "(--serve-recording)\n");
        } else {
            const ops::file_request file{options_.recording, "application/octet-stream",
                                         std::string(request[http::field::range]), head_only, false};
            co_await answer_file(conn, peer, file);
            co_return;
        }
    } else {
        static_refusal why;
        if (std::optional<static_file> found = files_.resolve(path, &why)) {
            const ops::file_request file{found->path, found->content_type, std::string(request[http::field::range]),
                                         head_only, false};
            co_await answer_file(conn, peer, file);
            co_return;
        }
        if (why.hostile)
            host::log_line("http: %s: refused path '%.*s': %s", peer.c_str(),
                           static_cast<int>(std::min<size_t>(path.size(), 200)), path.data(), why.reason.c_str());
        reply = text_response(why.status, "text/plain; charset=utf-8",
                              why.status == 404 ? "not found\n" : why.reason + "\n");
    }
    if (!*alive) co_return;
    if (reply) {
        conn->stream.expires_after(std::chrono::nanoseconds(options_.write_timeout_ns));
        ec = co_await write_reply(conn->stream, *reply, head_only);
        if (!*alive) co_return;
    }
    conn->stream.socket().shutdown(tcp::socket::shutdown_send, ec);
    conn->stream.socket().close(ec);
    forget_http(*conn);
}

boost::asio::awaitable<void> web_transport::answer_file(std::shared_ptr<http_conn> conn, const std::string& peer,
                                                        const ops::file_request& file) {
    const auto alive = alive_;
    // A download past its budget of slots makes room by ending the slowest one (a client that
    // does not read): page loads go on while /healthz and upgrades keep the rest.
    if (downloads_.size() >= options_.max_downloads) evict_slowest_download();
    conn->download_at = downloads_.insert(downloads_.end(), conn);
    conn->downloading = true;
    const ops::file_send_limits limits{options_.file_chunk_bytes, options_.min_download_bytes_per_second};
    const std::string why = co_await ops::send_file(conn->stream, file, limits, pacer_, conn->progress);
    if (!*alive) co_return;
    const bool evicted = !conn->counted;
    if (evicted) {
        host::log_line("http: %s: download ended to make room, after %llu bytes", peer.c_str(),
                       static_cast<unsigned long long>(conn->progress->sent));
    } else if (!why.empty()) {
        host::log_line("http: %s: download ended: %s", peer.c_str(), why.c_str());
    }
    boost::system::error_code ec;
    conn->stream.socket().shutdown(tcp::socket::shutdown_send, ec);
    conn->stream.socket().close(ec);
    forget_http(*conn);
}

}  // namespace arena::net
