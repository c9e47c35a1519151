#include "server_process.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>
#include <thread>

#include "protocol/verify.hpp"
#include "tests/common/descriptors.hpp"

namespace arena::test {

server_process::server_process(const std::vector<std::string>& args) {
    int out_pipe[2], err_pipe[2];
    if (::pipe(out_pipe) != 0 || ::pipe(err_pipe) != 0) throw std::runtime_error("pipe failed");
    const std::string binary = std::string(ARENA_BIN_DIR) + "/arena-server";
    std::vector<std::string> all = {binary, "--port", "0"};
    all.insert(all.end(), args.begin(), args.end());
    pid_ = ::fork();
    if (pid_ == 0) {
        ::dup2(out_pipe[1], 1);
        ::dup2(err_pipe[1], 2);
        close_inherited_descriptors();  // the server's descriptor budget is its own
        std::vector<char*> argv;
        for (auto& a : all) argv.push_back(a.data());
        argv.push_back(nullptr);
        ::execv(binary.c_str(), argv.data());
        ::_exit(127);
    }
    ::close(out_pipe[1]);
    ::close(err_pipe[1]);
    stdout_fd_ = out_pipe[0];
    stderr_fd_ = err_pipe[0];
    log_drain_ = std::thread([this] {
        char buf[4096];
        while (true) {
            const ssize_t n = ::read(stderr_fd_, buf, sizeof buf);
            if (n <= 0) break;
            std::lock_guard<std::mutex> lock(log_mutex_);
            log_.append(buf, static_cast<size_t>(n));
        }
    });
    std::string line;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (std::chrono::steady_clock::now() < deadline) {
        pollfd p{stdout_fd_, POLLIN, 0};
        if (::poll(&p, 1, 100) <= 0) continue;
        char c;
        if (::read(stdout_fd_, &c, 1) != 1) break;
        if (c != '\n') {
            line += c;
            continue;
        }
        const auto at = line.rfind(':');
        if (line.rfind("listening on ", 0) == 0 && at != std::string::npos) {
            port_ = static_cast<uint16_t>(std::stoi(line.substr(at + 1)));
            return;
        }
        line.clear();
    }
    stop(SIGKILL);
    log_drain_.join();
    throw std::runtime_error("arena-server did not print 'listening on': " + log());
}

uint16_t server_process::port_line(const std::string& prefix, std::chrono::milliseconds timeout) {
    std::string line;
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
        pollfd p{stdout_fd_, POLLIN, 0};
        if (::poll(&p, 1, 100) <= 0) continue;
        char c;
        if (::read(stdout_fd_, &c, 1) != 1) return 0;
        if (c != '\n') {
            line += c;
            continue;
        }
        const auto at = line.rfind(':');
        if (line.rfind(prefix + " ", 0) == 0 && at != std::string::npos)
            return static_cast<uint16_t>(std::stoi(line.substr(at + 1)));
        line.clear();
    }
    return 0;
}

server_process::~server_process() {
    if (pid_ > 0) stop(SIGKILL);
    if (log_drain_.joinable()) log_drain_.join();  // ends at EOF: the server has exited
    if (stdout_fd_ >= 0) ::close(stdout_fd_);
    if (stderr_fd_ >= 0) ::close(stderr_fd_);
}

int server_process::stop(int signal, std::chrono::milliseconds timeout) {
    if (pid_ <= 0) return -1;
    ::kill(pid_, signal);
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    int status = 0;
    while (std::chrono::steady_clock::now() < deadline) {
        if (::waitpid(pid_, &status, WNOHANG) == pid_) {
            pid_ = -1;
            return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    return -1;
}

long server_process::rss_kib() const {
    std::ifstream status("/proc/" + std::to_string(pid_) + "/status");
    std::string key;
    while (status >> key) {
        if (key == "VmRSS:") {
            long kib = 0;
            status >> kib;
            return kib;
        }
        status.ignore(1 << 12, '\n');
    }
    return -1;
}

std::string server_process::log() {
    std::lock_guard<std::mutex> lock(log_mutex_);
    return log_;
}

bool server_process::log_shows(const std::string& text, std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    for (;;) {
        if (log().find(text) != std::string::npos) return true;
        if (std::chrono::steady_clock::now() >= deadline) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
}

test_client::test_client(uint16_t port, int receive_buffer) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    if (receive_buffer > 0) ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &receive_buffer, sizeof receive_buffer);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(port);
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0)
        throw std::runtime_error(std::string("connect failed: ") + std::strerror(errno));
    int one = 1;
    ::setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
}

test_client::~test_client() {
    if (fd_ >= 0) ::close(fd_);
}

void test_client::send_bytes(const std::vector<uint8_t>& bytes) {
    size_t sent = 0;
    while (sent < bytes.size()) {
        const ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
        if (n <= 0) return;  // the server closed: the caller checks for that
        sent += static_cast<size_t>(n);
    }
}

bool test_client::fill(size_t want, std::chrono::steady_clock::time_point deadline) {
    while (buffer_.size() < want) {
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) return false;
        pollfd p{fd_, POLLIN, 0};
        if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) return false;
        uint8_t buf[65536];
        const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
        if (n <= 0) return false;
        buffer_.insert(buffer_.end(), buf, buf + n);
    }
    return true;
}

std::optional<std::vector<uint8_t>> test_client::read_frame(std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    if (!fill(4, deadline)) return std::nullopt;
    const uint32_t length = buffer_[0] | buffer_[1] << 8 | buffer_[2] << 16 | static_cast<uint32_t>(buffer_[3]) << 24;
    if (!fill(4 + length, deadline)) return std::nullopt;
    std::vector<uint8_t> frame(buffer_.begin(), buffer_.begin() + 4 + length);
    buffer_.erase(buffer_.begin(), buffer_.begin() + 4 + length);
    return frame;
}

std::optional<std::vector<uint8_t>> test_client::read_until(protocol::Payload type, std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (true) {
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) return std::nullopt;
        auto frame = read_frame(left);
        if (!frame) return std::nullopt;
        const protocol::Message* m = message_of(*frame);
        if (m && m->payload_type() == type) return frame;
    }
}

bool test_client::closed_by_peer(std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
        pollfd p{fd_, POLLIN, 0};
        if (::poll(&p, 1, 50) <= 0) continue;
        uint8_t buf[65536];
        const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
        if (n == 0) return true;
        if (n < 0) return errno == ECONNRESET;
    }
    return false;
}

const protocol::Message* message_of(const std::vector<uint8_t>& frame) {
    auto verified = protocol::verify_message(frame, protocol::server_frame_limits);
    return verified ? verified.value : nullptr;
}

std::string temp_path(const std::string& name) {
    // Every path handed out is removed when the test process ends, whatever the test did with it.
    struct removed_at_exit {
        std::set<std::string> paths;
        ~removed_at_exit() {
            for (const std::string& p : paths) std::remove(p.c_str());
        }
    };
    static removed_at_exit scratch;
    std::string path = "/tmp/arena-test-" + std::to_string(::getpid()) + "-" + name;
    scratch.paths.insert(path);
    return path;
}

std::string read_file(const std::string& path) {
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

namespace {

std::vector<std::string> with_free_port(std::vector<std::string> args, const std::string& flag) {
    args.insert(args.end(), {flag, "0"});
    return args;
}

uint16_t listening_port(server_process& process, const std::string& line) {
    const uint16_t port = process.port_line(line);
    if (port == 0) throw std::runtime_error("arena-server printed no \"" + line + " HOST:PORT\" line");
    return port;
}

}  // namespace

udp_server::udp_server(std::vector<std::string> args)
    : process(with_free_port(std::move(args), "--udp-port")), udp_port(listening_port(process, "udp listening on")) {}

http_server::http_server(std::vector<std::string> args)
    : process(with_free_port(std::move(args), "--http-port")),
      http_port(listening_port(process, "http listening on")) {}

}  // namespace arena::test
