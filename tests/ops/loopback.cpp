#include "tests/ops/loopback.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <future>
#include <stdexcept>

namespace arena::test {

using clock_type = std::chrono::steady_clock;

namespace {

sockaddr_in loopback(uint16_t port) {
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(port);
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    return addr;
}

bool readable(int fd, clock_type::time_point deadline) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - clock_type::now()).count();
    if (left <= 0) return false;
    pollfd p{fd, POLLIN, 0};
    return poll(&p, 1, static_cast<int>(left)) == 1;
}

}  // namespace

namespace {

std::string exchange_at(sockaddr_in addr, const std::string& request, std::chrono::milliseconds timeout) {
    const auto deadline = clock_type::now() + timeout;
    const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
        close(fd);
        return "";
    }
    // A server may answer (431) and close before taking all of an oversize request: a failed
    // send is not the end of the exchange.
    size_t sent = 0;
    while (sent < request.size()) {
        const ssize_t n = send(fd, request.data() + sent, request.size() - sent, MSG_NOSIGNAL);
        if (n <= 0) break;
        sent += static_cast<size_t>(n);
    }
    std::string response =
        read_until_closed(fd, std::chrono::duration_cast<std::chrono::milliseconds>(deadline - clock_type::now()));
    close(fd);
    return response;
}

}  // namespace

std::string http_exchange(uint16_t port, const std::string& request, std::chrono::milliseconds timeout) {
    return exchange_at(loopback(port), request, timeout);
}

std::string http_get_at(const std::string& ipv4, uint16_t port, const std::string& path) {
    sockaddr_in addr = loopback(port);
    if (inet_pton(AF_INET, ipv4.c_str(), &addr.sin_addr) != 1) throw std::runtime_error("not an IPv4 address");
    return exchange_at(addr, "GET " + path + " HTTP/1.1\r\nHost: " + ipv4 + "\r\nConnection: close\r\n\r\n",
                       std::chrono::milliseconds(3000));
}

std::string read_until_closed(int fd, std::chrono::milliseconds timeout) {
    const auto deadline = clock_type::now() + timeout;
    std::string response;
    char buffer[4096];
    while (readable(fd, deadline)) {
        const ssize_t n = recv(fd, buffer, sizeof buffer, 0);
        if (n <= 0) break;
        response.append(buffer, static_cast<size_t>(n));
    }
    return response;
}

std::string http_get(uint16_t port, const std::string& path) {
    return http_exchange(port, "GET " + path + " HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n\r\n");
}

int status_of(const std::string& response) {
    if (response.size() < 12 || response.compare(0, 7, "HTTP/1.") != 0) return 0;
    return std::stoi(response.substr(9, 3));
}

int open_idle_connection(uint16_t port) {
    const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in addr = loopback(port);
    if (connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
        close(fd);
        return -1;
    }
    return fd;
}

bool closed_by_peer(int fd, std::chrono::milliseconds wait) {
    if (!readable(fd, clock_type::now() + wait)) return false;
    char byte = 0;
    return recv(fd, &byte, 1, MSG_DONTWAIT) <= 0;
}

uint16_t free_port() {
    const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in addr = loopback(0);
    socklen_t len = sizeof addr;
    if (bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
        getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0)
        throw std::runtime_error("free_port: cannot bind");
    close(fd);
    return ntohs(addr.sin_port);
}

silent_listener::silent_listener() {
    fd_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in addr = loopback(0);
    socklen_t len = sizeof addr;
    if (fd_ < 0 || bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 || listen(fd_, 4) != 0 ||
        getsockname(fd_, reinterpret_cast<sockaddr*>(&addr), &len) != 0) {
        if (fd_ >= 0) close(fd_);
        throw std::runtime_error("silent_listener: cannot listen on 127.0.0.1");
    }
    port_ = ntohs(addr.sin_port);
}

silent_listener::~silent_listener() {
    close(fd_);
}

fake_sidecar::fake_sidecar(uint16_t port, std::chrono::milliseconds start_delay) {
    port_ = port ? port : free_port();
    thread_ = std::thread([this, start_delay] { run(start_delay); });
}

fake_sidecar::~fake_sidecar() {
    stop_ = true;
    thread_.join();
    if (listen_fd_ >= 0) close(listen_fd_);
}

void fake_sidecar::run(std::chrono::milliseconds start_delay) {
    const auto start = clock_type::now() + start_delay;
    while (!stop_ && clock_type::now() < start) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (stop_) return;
    listen_fd_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    const int one = 1;
    setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    sockaddr_in addr = loopback(port_);
    if (bind(listen_fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 || listen(listen_fd_, 16) != 0) return;
    listening_since_ = clock_type::now();
    while (!stop_) {
        pollfd p{listen_fd_, POLLIN, 0};
        if (poll(&p, 1, 20) != 1) continue;
        const int fd = accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
        if (fd < 0) continue;
        serve(fd);
        close(fd);
    }
}

void fake_sidecar::serve(int fd) {
    const auto arrived = clock_type::now();
    const auto deadline = arrived + std::chrono::seconds(2);
    std::string request;
    char buffer[1024];
    size_t head_end = std::string::npos;
    size_t body_length = 0;
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
    if (head_end == std::string::npos) return;
    call c;
    const size_t space = request.find(' ');
    c.method = request.substr(0, space);
    c.path = request.substr(space + 1, request.find(' ', space + 1) - space - 1);
    c.body = request.substr(head_end + 4, body_length);
    c.at = arrived;
    {
        std::lock_guard lock(mutex_);
        calls_.push_back(c);
    }
    const int status = status_;
    const std::string body = status == 200 ? "{}" : "{\"error\":\"test\"}";
    const std::string response =
        "HTTP/1.1 " + std::to_string(status) + (status == 200 ? " OK" : " Error") +
        "\r\nContent-Type: application/json\r\nContent-Length: " + std::to_string(body.size()) +
        "\r\nConnection: close\r\n\r\n" + body;
    send(fd, response.data(), response.size(), MSG_NOSIGNAL);
}

std::vector<fake_sidecar::call> fake_sidecar::calls() const {
    std::lock_guard lock(mutex_);
    return calls_;
}

size_t fake_sidecar::count(const std::string& path) const {
    size_t n = 0;
    for (const call& c : calls()) n += c.path == path;
    return n;
}

bool fake_sidecar::wait_until(const std::function<bool(const std::vector<call>&)>& done,
                              std::chrono::milliseconds timeout) const {
    const auto deadline = clock_type::now() + timeout;
    while (clock_type::now() < deadline) {
        if (done(calls())) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return done(calls());
}

void io_thread::run_on_io(std::function<void()> f) {
    std::promise<void> finished;
    boost::asio::post(io_, [&] {
        f();
        finished.set_value();
    });
    finished.get_future().wait();
}

}  // namespace arena::test
