#pragma once
// Test helpers for the ops endpoints, in plain POSIX so that the fakes cannot share a bug with
// the Asio code under test: a raw HTTP exchange, a fake Agones sidecar that records calls, and
// an io_context running on its own thread.
#include <boost/asio.hpp>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace arena::test {

// Sends `request` to 127.0.0.1:port and returns everything the server wrote until it closed
// (or the timeout). "" when the connection failed.
std::string http_exchange(uint16_t port, const std::string& request,
                          std::chrono::milliseconds timeout = std::chrono::milliseconds(3000));
std::string http_get(uint16_t port, const std::string& path);
// The same to another address (127.0.0.2: the whole 127/8 is loopback on Linux).
std::string http_get_at(const std::string& ipv4, uint16_t port, const std::string& path);
// The status code of a raw response, 0 when none.
int status_of(const std::string& response);
// A connection to 127.0.0.1:port that sends nothing (-1 when connect failed); the caller closes it.
int open_idle_connection(uint16_t port);
// Everything the peer sends on `fd` until it closes (or the timeout passes).
std::string read_until_closed(int fd, std::chrono::milliseconds timeout);
// True when the peer closed `fd` (or reset it) within `wait`; false while it stays open.
bool closed_by_peer(int fd, std::chrono::milliseconds wait);
// A port nobody listens on right now (bound to 0, then released).
uint16_t free_port();

// A socket listening on 127.0.0.1 that nobody accepts from: the kernel completes a client's
// handshake, then silence. Plays a peer that takes the connection and never answers.
class silent_listener {
public:
    silent_listener();
    ~silent_listener();
    silent_listener(const silent_listener&) = delete;
    silent_listener& operator=(const silent_listener&) = delete;

    uint16_t port() const { return port_; }
    int fd() const { return fd_; }

private:
    int fd_ = -1;
    uint16_t port_ = 0;
};

// A stand-in for the Agones SDK sidecar's REST server: answers every request with `status`
// and records method, path, body and arrival time.
class fake_sidecar {
public:
    struct call {
        std::string method, path, body;
        std::chrono::steady_clock::time_point at;
    };
    // Listens on `port` (0: any) after `start_delay` (to play a sidecar that starts late).
    explicit fake_sidecar(uint16_t port = 0, std::chrono::milliseconds start_delay = std::chrono::milliseconds(0));
    ~fake_sidecar();
    fake_sidecar(const fake_sidecar&) = delete;
    fake_sidecar& operator=(const fake_sidecar&) = delete;

    uint16_t port() const { return port_; }
    std::vector<call> calls() const;
    size_t count(const std::string& path) const;
    // Polls until `done(calls())` holds or the timeout passes.
    bool wait_until(const std::function<bool(const std::vector<call>&)>& done, std::chrono::milliseconds timeout) const;
    void set_status(int status) { status_ = status; }
    std::chrono::steady_clock::time_point listening_since() const { return listening_since_.load(); }

private:
    void run(std::chrono::milliseconds start_delay);
    void serve(int fd);

    uint16_t port_ = 0;
    int listen_fd_ = -1;
    std::atomic<bool> stop_{false};
    std::atomic<int> status_{200};
    std::atomic<std::chrono::steady_clock::time_point> listening_since_{};
    mutable std::mutex mutex_;
    std::vector<call> calls_;
    std::thread thread_;
};

// Runs an io_context on a thread until destroyed. Declare it after the objects that use the
// io_context, so that it stops first.
class io_thread {
public:
    explicit io_thread(boost::asio::io_context& io)
        : io_(io), guard_(boost::asio::make_work_guard(io)), thread_([this] { io_.run(); }) {}
    ~io_thread() {
        io_.stop();
        thread_.join();
    }
    // Runs f on the io thread and waits for it: the objects under test are not thread-safe.
    void run_on_io(std::function<void()> f);

private:
    boost::asio::io_context& io_;
    boost::asio::executor_work_guard<boost::asio::io_context::executor_type> guard_;
    std::thread thread_;
};

}  // namespace arena::test
