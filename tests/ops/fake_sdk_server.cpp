#include "tests/ops/fake_sdk_server.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace arena::test {

namespace {

using clock_type = std::chrono::steady_clock;
using nlohmann::json;

bool readable(int fd, clock_type::time_point deadline) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - clock_type::now()).count();
    if (left <= 0) return false;
    pollfd p{fd, POLLIN, 0};
    return poll(&p, 1, static_cast<int>(left)) == 1;
}

void send_all(int fd, const std::string& bytes) {
    size_t sent = 0;
    while (sent < bytes.size()) {
        const ssize_t n = send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
        if (n <= 0) return;
        sent += static_cast<size_t>(n);
    }
}

// One event of the watch as grpc-gateway streams it: a line of JSON, in one HTTP chunk.
std::string chunk(const std::string& line) {
    char size[32];
    std::snprintf(size, sizeof size, "%zx\r\n", line.size() + 1);
    return size + line + "\n\r\n";
}

std::string error_json(int code, const std::string& message) {
    return json{{"code", code}, {"message", message}, {"details", json::array()}}.dump();
}

// An int64 of a request body: a JSON string, as grpc-gateway writes it, or a number.
std::optional<int64_t> int64_of(const json& j) {
    if (j.is_number_integer()) return j.get<int64_t>();
    if (!j.is_string()) return std::nullopt;
    try {
        size_t used = 0;
        const std::string s = j.get<std::string>();
        const long long v = std::stoll(s, &used);
        return used == s.size() ? std::optional<int64_t>(v) : std::nullopt;
    } catch (const std::exception&) {
        return std::nullopt;
    }
}

}  // namespace

fake_sdk_server::fake_sdk_server(setup s) {
    rooms_capacity_ = s.rooms_capacity;
    if (rooms_capacity_) rooms_count_ = 0;
    players_capacity_ = s.players_capacity;
    listen_fd_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof addr;
    if (bind(listen_fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 || listen(listen_fd_, 32) != 0 ||
        getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&addr), &len) != 0)
        throw std::runtime_error("fake_sdk_server: cannot listen");
    port_ = ntohs(addr.sin_port);
    acceptor_ = std::thread([this] { accept_loop(); });
}

fake_sdk_server::~fake_sdk_server() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
        for (const int fd : watch_fds_) shutdown(fd, SHUT_RDWR);
    }
    acceptor_.join();
    for (auto& t : threads_) t.join();
    for (const int fd : watch_fds_) close(fd);
    close(listen_fd_);
}

void fake_sdk_server::accept_loop() {
    for (;;) {
        {
            std::lock_guard lock(mutex_);
            if (stop_) return;
        }
        pollfd p{listen_fd_, POLLIN, 0};
        if (poll(&p, 1, 20) != 1) continue;
        const int fd = accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
        if (fd < 0) continue;
        threads_.emplace_back([this, fd] { serve(fd); });
    }
}

void fake_sdk_server::serve(int fd) {
    const auto deadline = clock_type::now() + std::chrono::seconds(2);
    std::string request;
    char buffer[2048];
    size_t head_end = std::string::npos, body_length = 0;
    while (readable(fd, deadline)) {
        const ssize_t n = recv(fd, buffer, sizeof buffer, 0);
        if (n <= 0) break;
        request.append(buffer, static_cast<size_t>(n));
        if (head_end == std::string::npos && (head_end = request.find("\r\n\r\n")) != std::string::npos) {
            const size_t at = request.find("Content-Length: ");
            if (at != std::string::npos && at < head_end) body_length = std::stoul(request.substr(at + 16));
        }
        if (head_end != std::string::npos && request.size() >= head_end + 4 + body_length) break;
    }
    if (head_end == std::string::npos) {
        close(fd);
        return;
    }
    const size_t space = request.find(' ');
    const std::string method = request.substr(0, space);
    const std::string path = request.substr(space + 1, request.find(' ', space + 1) - space - 1);
    const std::string body = request.substr(head_end + 4, body_length);

    std::unique_lock lock(mutex_);
    answer a;
    bool changed = false;
    const auto failure = std::find_if(failures_.begin(), failures_.end(), [&](const injected_failure& f) {
        return f.left > 0 && f.method == method && path.compare(0, f.path.size(), f.path) == 0;
    });
    if (failure != failures_.end()) {
        --failure->left;
        a = answer{failure->status, error_json(13, "injected failure")};
    } else if (method == "GET" && path == "/watch/gameserver") {
        calls_.push_back({method, path, body, 200});
        send_all(fd, "HTTP/1.1 200 OK\r\nContent-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n" +
                         chunk(json{{"result", json::parse(gameserver_json())}}.dump()));
        watch_fds_.push_back(fd);  // kept open: broadcast() writes to it
        return;
    } else {
        a = route(method, path, body, changed);
    }
    calls_.push_back({method, path, body, a.status});
    if (changed) broadcast();
    lock.unlock();
    send_all(fd, "HTTP/1.1 " + std::to_string(a.status) + (a.status < 300 ? " OK" : " Error") +
                     "\r\nContent-Type: application/json\r\nContent-Length: " + std::to_string(a.body.size()) +
                     "\r\nConnection: close\r\n\r\n" + a.body);
    close(fd);
}

fake_sdk_server::answer fake_sdk_server::route(const std::string& method, const std::string& path,
                                               const std::string& body, bool& changed) {
    const std::string counters = "/v1beta1/counters/", lists = "/v1beta1/lists/";
    if (method == "POST" && (path == "/ready" || path == "/health" || path == "/shutdown")) {
        if (path != "/health") {
            state_ = path == "/ready" ? "Ready" : "Shutdown";
            changed = true;
        }
        return {};
    }
    if (path.compare(0, counters.size(), counters) == 0) {
        const std::string name = path.substr(counters.size());
        if (name != "rooms" || !rooms_count_) return {404, error_json(5, "counter not found: " + name)};
        if (method == "GET")
            return {200, json{{"name", name},
                              {"count", std::to_string(*rooms_count_)},
                              {"capacity", std::to_string(*rooms_capacity_)}}
                             .dump()};
        if (method != "PATCH") return {405, error_json(12, "method not allowed")};
        const json j = json::parse(body, nullptr, false);
        const auto diff = j.is_object() && j.contains("countDiff") ? int64_of(j["countDiff"]) : std::nullopt;
        if (!diff) return {400, error_json(3, "invalid countDiff")};
        const int64_t count = *rooms_count_ + *diff;
        if (count < 0 || count > *rooms_capacity_)
            return {500, error_json(2, "out of range. Count must be within range [0,Capacity]. Found Count: " +
                                           std::to_string(count) + ", Capacity: " + std::to_string(*rooms_capacity_))};
        rooms_count_ = count;
        changed = true;
        return {200, "{}"};  // before Agones 1.54: an empty Counter
    }
    if (path.compare(0, lists.size(), lists) == 0) {
        const std::string rest = path.substr(lists.size());
        const size_t colon = rest.find(':');
        const std::string name = rest.substr(0, colon), verb = colon == std::string::npos ? "" : rest.substr(colon + 1);
        if (name != "players" || !players_capacity_) return {404, error_json(5, "list not found: " + name)};
        if (method == "GET" && verb.empty())
            return {
                200,
                json{{"name", name}, {"capacity", std::to_string(*players_capacity_)}, {"values", players_}}.dump()};
        const json j = json::parse(body, nullptr, false);
        if (method != "POST" || !j.is_object() || !j.contains("value") || !j["value"].is_string())
            return {400, error_json(3, "invalid request")};
        const std::string value = j["value"].get<std::string>();
        const auto it = std::find(players_.begin(), players_.end(), value);
        if (verb == "addValue") {
            if (static_cast<int64_t>(players_.size()) >= *players_capacity_)
                return {500, error_json(2, "out of range. No available capacity.")};
            if (it != players_.end())
                return {500, error_json(2, "already exists. Value: " + value + " already in List: " + name)};
            players_.push_back(value);
        } else if (verb == "removeValue") {
            if (it == players_.end())
                return {500, error_json(2, "not found. Value: " + value + " not found in List: " + name)};
            players_.erase(it);
        } else {
            return {404, error_json(5, "no such method")};
        }
        changed = true;
        return {200, "{}"};
    }
    return {404, error_json(5, "Not Found")};
}

std::string fake_sdk_server::gameserver_json() const {
    json status{{"state", state_}, {"address", "127.0.0.1"}};
    if (rooms_count_)
        status["counters"]["rooms"] = {{"count", std::to_string(*rooms_count_)},
                                       {"capacity", std::to_string(*rooms_capacity_)}};
    if (players_capacity_)
        status["lists"]["players"] = {{"capacity", std::to_string(*players_capacity_)}, {"values", players_}};
    json meta{{"name", "arena-fake"}, {"namespace", "default"}};
    meta["annotations"] = annotations_.empty() ? json::object() : json(annotations_);
    return json{{"object_meta", meta}, {"status", status}}.dump();
}

void fake_sdk_server::broadcast() {
    const std::string event = chunk(json{{"result", json::parse(gameserver_json())}}.dump());
    for (const int fd : watch_fds_) send_all(fd, event);
}

bool fake_sdk_server::allocate(const std::string& mode, const std::string& match) {
    std::lock_guard lock(mutex_);
    if (rooms_count_) {
        if (*rooms_count_ >= *rooms_capacity_) return false;
        ++*rooms_count_;
    }
    state_ = "Allocated";
    annotations_["agones.dev/last-allocated"] = "2026-01-01T00:00:" + std::to_string(10 + ++allocations_) + "Z";
    if (mode.empty()) {
        annotations_.erase("arena.dev/mode");
    } else {
        annotations_["arena.dev/mode"] = mode;
    }
    if (match.empty()) {
        annotations_.erase("arena.dev/match");
    } else {
        annotations_["arena.dev/match"] = match;
    }
    broadcast();
    return true;
}

void fake_sdk_server::fail_next(const std::string& method, const std::string& path, int status, int n) {
    std::lock_guard lock(mutex_);
    failures_.push_back({method, path, status, n});
}

void fake_sdk_server::drop_watches() {
    std::lock_guard lock(mutex_);
    for (const int fd : watch_fds_) {
        shutdown(fd, SHUT_RDWR);
        close(fd);
    }
    watch_fds_.clear();
}

size_t fake_sdk_server::watchers() const {
    std::lock_guard lock(mutex_);
    return watch_fds_.size();
}

std::vector<fake_sdk_server::call> fake_sdk_server::calls() const {
    std::lock_guard lock(mutex_);
    return calls_;
}

size_t fake_sdk_server::count(const std::string& method, const std::string& path) const {
    size_t n = 0;
    for (const call& c : calls()) n += c.method == method && c.path.compare(0, path.size(), path) == 0;
    return n;
}

std::optional<int64_t> fake_sdk_server::rooms() const {
    std::lock_guard lock(mutex_);
    return rooms_count_;
}

std::vector<std::string> fake_sdk_server::players() const {
    std::lock_guard lock(mutex_);
    return players_;
}

std::string fake_sdk_server::state() const {
    std::lock_guard lock(mutex_);
    return state_;
}

bool fake_sdk_server::wait_until(const std::function<bool()>& done, std::chrono::milliseconds timeout) {
    const auto deadline = clock_type::now() + timeout;
    while (clock_type::now() < deadline) {
        if (done()) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return done();
}

}  // namespace arena::test
