#pragma once
// A client of the Agones SDK sidecar's REST API (https://agones.dev/site/docs/guides/client-sdks/rest/):
// POST /ready once the game port listens, POST /health every interval while the tick loop
// advances, POST /shutdown when the match ends. Agones marks a server Unhealthy when pings
// stop, so they are sent only while `healthy()` says the world is really stepping: a wedged
// tick loop must look dead even though this io thread still runs.
// With keep_density(), it also keeps the Counter `rooms` and the List `players` true and hears
// allocations (density_sync.hpp): high density, many matches in one game server.
#include <boost/asio.hpp>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "server/ops/density_reconciler.hpp"

namespace arena::ops {

struct agones_options {
    std::string host = "127.0.0.1";               // the sidecar shares the pod's loopback
    uint16_t port = 9358;                         // AGONES_SDK_HTTP_PORT
    int64_t health_interval_ns = 2'000'000'000;   // between /health pings
    int64_t request_timeout_ns = 1'000'000'000;   // one request, connect to response head
    int64_t retry_initial_ns = 100'000'000;       // first retry of /ready or /shutdown
    int64_t retry_max_ns = 2'000'000'000;         // retries double up to this
    int64_t shutdown_timeout_ns = 5'000'000'000;  // /shutdown gives up after this
};

using log_fn = std::function<void(const std::string&)>;

class density_sync;

class agones_client {
public:
    agones_client(boost::asio::io_context& io, agones_options options, std::function<bool()> healthy, log_fn log);
    ~agones_client();

    // POST /ready (retrying with backoff until the sidecar answers 2xx), then the health pings.
    void start();
    // Stops the pings and POSTs /shutdown (retrying), then calls `done` once, on the io thread:
    // after the sidecar accepted, or after shutdown_timeout_ns, whichever comes first.
    // Idempotent: a second call's `done` is called too.
    void shutdown(std::function<void()> done);

    // High density: from start() on, keep `rooms` and `players` at what want_density() last
    // said, and call `on_allocation` (on the io thread) for each allocation the GameServer
    // watch shows. Call before start(); the process must call want_density() from within
    // `on_allocation` once it created the match, so that `rooms` never counts it twice.
    void keep_density(std::function<void(const allocation_request&)> on_allocation);
    void want_density(density_state desired);
    // The sync, once keep_density() was called (tests read its state).
    const density_sync* density() const { return density_.get(); }

    bool is_ready() const { return ready_; }
    uint64_t health_pings() const { return health_pings_; }

private:
    boost::asio::awaitable<void> run();
    boost::asio::awaitable<bool> post(const char* path);
    boost::asio::awaitable<void> sleep(int64_t ns);
    void finish_shutdown(const char* how);

    boost::asio::io_context& io_;
    agones_options options_;
    std::function<bool()> healthy_;
    log_fn log_;
    boost::asio::steady_timer wake_;      // the sleep between attempts; shutdown() cuts it short
    boost::asio::steady_timer deadline_;  // bounds the shutdown phase
    bool started_ = false;
    bool stopping_ = false;
    bool finished_ = false;
    bool ready_ = false;
    uint64_t health_pings_ = 0;
    std::vector<std::function<void()>> done_;
    std::unique_ptr<density_sync> density_;
};

}  // namespace arena::ops
