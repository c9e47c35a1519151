// arena-healthcheck: GET a URL on loopback and exit 0 on HTTP 200, 1 otherwise. The runtime
// image has no curl and should not grow one (and its libcurl and TLS stack) for a probe of our
// own endpoint: Docker's HEALTHCHECK runs this instead.
//   arena-healthcheck [http://127.0.0.1:8080/healthz] [--timeout SECONDS]
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "server/ops/http_message.hpp"

namespace {

struct target {
    std::string host;
    uint16_t port = 0;
    std::string path;
};

// Only what the probe needs: http://IPV4:PORT/PATH.
bool parse_url(const std::string& url, target& out) {
    const std::string scheme = "http://";
    if (url.rfind(scheme, 0) != 0) return false;
    const size_t host_end = url.find(':', scheme.size());
    if (host_end == std::string::npos) return false;
    const size_t slash = url.find('/', host_end);
    out.host = url.substr(scheme.size(), host_end - scheme.size());
    const std::string port =
        url.substr(host_end + 1, slash == std::string::npos ? std::string::npos : slash - host_end - 1);
    out.path = slash == std::string::npos ? "/" : url.substr(slash);
    char* end = nullptr;
    const long p = std::strtol(port.c_str(), &end, 10);
    if (port.empty() || *end || p < 1 || p > 65535) return false;
    out.port = static_cast<uint16_t>(p);
    return true;
}

// Waits for `events` on fd until the deadline; false on timeout or error.
bool wait_for(int fd, short events, std::chrono::steady_clock::time_point deadline) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    pollfd p{fd, events, 0};
    return poll(&p, 1, static_cast<int>(left.count())) == 1 && (p.revents & (events | POLLHUP));
}

int probe(const target& t, double timeout_s) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::milliseconds(static_cast<int64_t>(timeout_s * 1000));
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(t.port);
    if (inet_pton(AF_INET, t.host.c_str(), &addr.sin_addr) != 1) {
        std::fprintf(stderr, "arena-healthcheck: not an IPv4 address: %s\n", t.host.c_str());
        return 1;
    }
    const int fd = socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) return 1;
    int status = 0;
    if (connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0 || errno == EINPROGRESS) {
        int error = 0;
        socklen_t len = sizeof error;
        const std::string request = "GET " + t.path + " HTTP/1.1\r\nHost: " + t.host + "\r\nConnection: close\r\n\r\n";
        if (wait_for(fd, POLLOUT, deadline) && getsockopt(fd, SOL_SOCKET, SO_ERROR, &error, &len) == 0 && error == 0 &&
            send(fd, request.data(), request.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(request.size())) {
            std::string response;
            char buffer[512];
            // The status line is all we need.
            while (response.size() < 12 && wait_for(fd, POLLIN, deadline)) {
                const ssize_t n = recv(fd, buffer, sizeof buffer, 0);
                if (n <= 0) break;
                response.append(buffer, static_cast<size_t>(n));
            }
            status = arena::ops::parse_response_status(response);
        }
    }
    close(fd);
    std::printf("%s:%u%s -> %d\n", t.host.c_str(), t.port, t.path.c_str(), status);
    return status == 200 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    std::string url = "http://127.0.0.1:8080/healthz";
    double timeout_s = 2;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--timeout" && i + 1 < argc)
            timeout_s = std::atof(argv[++i]);
        else if (arg == "--help" || arg == "-h") {
            std::printf(
                "usage: arena-healthcheck [http://IPV4:PORT/PATH] [--timeout SECONDS]\n"
                "exit 0 when the URL answers HTTP 200 within the timeout (default 2 s), 1 otherwise\n");
            return 0;
        } else
            url = arg;
    }
    target t;
    if (!parse_url(url, t) || !(timeout_s > 0)) {
        std::fprintf(stderr, "arena-healthcheck: expected http://IPV4:PORT/PATH and a positive --timeout\n");
        return 2;
    }
    return probe(t, timeout_s);
}
