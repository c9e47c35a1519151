#pragma once
// A stand-in for the Agones SDK sidecar's REST server with Counters and Lists, as
// `sdk-server --local --test` plays it: it keeps a GameServer (annotations, state, a Counter
// `rooms`, a List `players`), answers the calls with Agones' semantics, streams the GameServer
// on GET /watch/gameserver after every change, and records every call for the test to check.
// Semantics kept: int64s are JSON strings; 0 <= count <= capacity (a change beyond is refused);
// an unknown Counter or List is an error; a List refuses a value it holds, or one beyond its
// capacity, and the removal of one it does not hold. Plain POSIX and a thread per connection,
// so that it shares no code with the client under test.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace arena::test {

class fake_sdk_server {
public:
    struct setup {
        std::optional<int64_t> rooms_capacity = 10;     // nullopt: the GameServer declares no Counter `rooms`
        std::optional<int64_t> players_capacity = 100;  // nullopt: no List `players`
    };
    struct call {
        std::string method, path, body;
        int status = 0;  // what the fake answered
    };

    explicit fake_sdk_server(setup s);
    fake_sdk_server() : fake_sdk_server(setup{}) {}
    ~fake_sdk_server();
    fake_sdk_server(const fake_sdk_server&) = delete;
    fake_sdk_server& operator=(const fake_sdk_server&) = delete;

    uint16_t port() const { return port_; }
    std::vector<call> calls() const;
    // Calls whose method is `method` and whose path starts with `path`.
    size_t count(const std::string& method, const std::string& path) const;
    std::optional<int64_t> rooms() const;
    std::vector<std::string> players() const;
    std::string state() const;

    // What the allocator does: the GameServer becomes Allocated with these annotations and a
    // new agones.dev/last-allocated, `rooms` goes up by one (false, and nothing changes, when it
    // is full), and the watchers get the GameServer.
    bool allocate(const std::string& mode, const std::string& match);
    // The next `n` calls of `method` to a path starting with `path` answer `status`.
    void fail_next(const std::string& method, const std::string& path, int status, int n);
    // Ends every watch stream (a sidecar restart); the client should reconnect.
    void drop_watches();
    size_t watchers() const;

    // Polls `done` until it holds or the timeout passes.
    static bool wait_until(const std::function<bool()>& done, std::chrono::milliseconds timeout);

private:
    struct answer {
        int status = 200;
        std::string body = "{}";
    };
    struct injected_failure {
        std::string method, path;
        int status = 500;
        int left = 0;
    };
    void accept_loop();
    void serve(int fd);
    answer route(const std::string& method, const std::string& path, const std::string& body, bool& changed);
    std::string gameserver_json() const;  // under mutex_
    void broadcast();                     // under mutex_

    uint16_t port_ = 0;
    int listen_fd_ = -1;
    bool stop_ = false;
    mutable std::mutex mutex_;
    std::vector<call> calls_;
    std::vector<injected_failure> failures_;
    std::optional<int64_t> rooms_count_, rooms_capacity_, players_capacity_;
    std::vector<std::string> players_;
    std::map<std::string, std::string> annotations_;
    std::string state_ = "Scheduled";
    int allocations_ = 0;
    std::vector<int> watch_fds_;
    std::vector<std::thread> threads_;
    std::thread acceptor_;
};

}  // namespace arena::test
