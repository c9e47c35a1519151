#pragma once
// The HTTP port (--http-port): one listening socket, Boost.Beast on the server's io_context
// thread, serving
//   /ws                  the game over WebSocket (ws_session.hpp): one binary message per frame;
//   /metrics, /healthz   the ops routes (server/ops/http_routes.hpp), as on --metrics-port;
//   /, anything else     files under the web root (static_files.hpp), else 404.
// Plain HTTP is one request per connection (Connection: close). Every connection that has not
// become a WebSocket is bounded like the ops endpoint: its request head in size and time, at
// most max_http_connections at once. When they are all taken, a new connection takes the slot
// of the oldest still sending its head, else of the slowest download; file answers (downloads)
// hold at most max_downloads of the slots, so that /healthz and WebSocket upgrades always have
// some, and each goes in chunks at a minimum rate (server/ops/file_answer.hpp). An upgraded
// connection is the match's, whose admission counts it with TCP's. Its stall watchdog is its own
// 250 ms timer, so that it runs while the host drains as well.
// Beast stays in web_transport.cpp and ws_session.cpp (it is heavy to compile).
#include <boost/asio.hpp>
#include <cstdint>
#include <filesystem>
#include <list>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "server/host/transport.hpp"
#include "server/net/static_files.hpp"
#include "server/ops/accept_backoff.hpp"
#include "server/ops/http_routes.hpp"

namespace arena::ops {
class file_pacer;  // file_answer.hpp
struct file_request;
}  // namespace arena::ops

namespace arena::net {

class ws_session;
struct http_conn;  // web_transport.cpp

struct web_options {
    uint16_t port = 0;                // 0: any free port
    std::filesystem::path web_root;   // empty: no files are served
    std::filesystem::path recording;  // --record's file; empty: /recording is a 404
    // --serve-recording: /recording (every body's position) is served on this port only once the
    // match has ended; while it runs, only on the metrics port (server/ops/http_server.hpp).
    bool serve_recording = false;
    bool serve_metrics = true;  // false with --metrics-port: /metrics only on its private address
    // Empty: the page's own origin (Origin's host:port equal to Host), or no Origin at all (a
    // program, not a browser), may open /ws; otherwise these origins only ("*": any).
    std::vector<std::string> allowed_origins;
    size_t max_request_bytes = 8 * 1024;                 // request line + headers; more gets 431
    uint32_t max_http_connections = 64;                  // not upgraded (heads being sent, answers being written)
    uint32_t max_downloads = 48;                         // of those, file answers; the rest stay for /healthz and /ws
    int64_t write_timeout_ns = 10'000'000'000;           // a small answer (not a file) must be written within this
    size_t file_chunk_bytes = 64 * 1024;                 // a file is read and written this much at a time
    uint64_t min_download_bytes_per_second = 16 * 1024;  // a chunk slower than this ends the download
    uint64_t file_bytes_per_second = 32 << 20;           // every download together, on the game's thread
    uint32_t max_ws_pings_per_second = 10;               // WebSocket pings (and unsolicited pongs): each costs a pong
    uint32_t ws_ping_burst = 20;
};

class web_transport final : public host::transport {
public:
    // handlers: what /metrics and /healthz answer (the ops service's).
    web_transport(host::transport_host& host, web_options options, ops::http_handlers handlers);
    ~web_transport() override;
    web_transport(const web_transport&) = delete;
    web_transport& operator=(const web_transport&) = delete;

    // Binds the server's --bind address, prints "http listening on HOST:PORT", and serves.
    void start() override;
    uint64_t open_connections() const override { return sessions_.size(); }
    uint16_t port() const { return port_; }

    // For the WebSocket sessions.
    host::transport_host& host() { return host_; }
    const web_options& options() const { return options_; }
    void on_open(const std::shared_ptr<ws_session>& s);
    void on_gone(ws_session& s);
    uint64_t next_session_id() { return next_session_id_++; }

    size_t websocket_connections() const { return sessions_.size(); }
    uint32_t http_connections() const { return http_open_; }
    uint64_t evicted_connections() const { return evicted_; }

private:
    boost::asio::awaitable<void> accept_loop();
    boost::asio::awaitable<void> serve(std::shared_ptr<http_conn> conn);
    // Answers a request head that was read whole; `leftover`: bytes the client sent after it.
    boost::asio::awaitable<void> answer(std::shared_ptr<http_conn> conn, const std::string& peer,
                                        std::vector<uint8_t> leftover);
    boost::asio::awaitable<void> answer_file(std::shared_ptr<http_conn> conn, const std::string& peer,
                                             const ops::file_request& file);
    bool origin_allowed(std::string_view origin, std::string_view host) const;
    void watch_stalls();
    void forget_http(http_conn& c);
    bool evict_oldest_waiting();
    bool evict_slowest_download();

    boost::asio::io_context& io_;
    host::transport_host& host_;
    web_options options_;
    ops::http_handlers handlers_;
    static_files files_;
    boost::asio::ip::tcp::acceptor acceptor_;
    ops::accept_backoff accept_backoff_;
    boost::asio::steady_timer watchdog_;
    uint16_t port_ = 0;
    std::shared_ptr<bool> alive_;                               // false once destroyed: coroutines still running stop
    std::map<uint64_t, std::shared_ptr<ws_session>> sessions_;  // upgraded, by id
    std::list<std::shared_ptr<http_conn>> waiting_;             // still sending their head, oldest first
    std::list<std::shared_ptr<http_conn>> downloads_;           // writing a file
    std::shared_ptr<ops::file_pacer> pacer_;                    // the downloads' byte rate
    uint32_t http_open_ = 0;
    uint64_t evicted_ = 0;
    uint64_t next_session_id_ = 1;
};

}  // namespace arena::net
