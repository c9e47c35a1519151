// arena-bench-tcp-floor: the least CPU a TCP server can spend on the Colyseus comparison's load
// (the server-CPU comparison in bench/README.md). K clients over loopback each send one small message per tick at 60
// Hz; the server sends each client one snapshot-sized message at 20 Hz. The server does nothing else: level-triggered
// epoll (no re-arming), one recv per readable socket, one send per snapshot, no parsing, no game. Its thread's CPU time
// (user + system) is the floor under Arena's and Colyseus' figures: whatever they spend above it is the game and the
// framework.
//
// The clients run on another thread pinned to another CPU, as arena-bots and Colyseus' load
// generator do. Over loopback the kernel does the receiving side's TCP work in the sender's
// context, so the server is charged for the snapshots it sends and for reading the inputs, as
// a real server is.
//
// Prints one JSON line.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sched.h>
#include <sys/epoll.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace {

using clock_type = std::chrono::steady_clock;

struct options {
    int clients = 200;
    double seconds = 20;
    int input_bytes = 72;      // an Input frame: length prefix, Message and Input tables
    int snapshot_bytes = 210;  // Arena's delta snapshot at 200 bots with the default view
    double input_hz = 60;
    double snapshot_hz = 20;
    int server_cpu = 1;
    int client_cpu = 0;
};

void fail(const std::string& what) {
    throw std::runtime_error(what + ": " + std::strerror(errno));
}

void pin_to(int cpu) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(cpu, &set);
    if (sched_setaffinity(0, sizeof set, &set) != 0) fail("sched_setaffinity");
}

double thread_cpu_seconds() {
    rusage u{};
    getrusage(RUSAGE_THREAD, &u);
    return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) / 1e6;
}

void no_delay(int fd) {
    const int one = 1;
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
}

// What the client thread tells the server thread.
struct client_state {
    std::atomic<bool> connected = false;
    std::atomic<bool> failed = false;  // `error` says why
    std::string error;
    std::atomic<bool> stop = false;
};

// Every `period` from `start`, sends one input on every socket, and reads whatever came back
// in between, until `stop`.
void run_clients(const options& o, uint16_t port, client_state& state) {
    pin_to(o.client_cpu);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(port);
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    const int poll = epoll_create1(0);
    std::vector<int> sockets;
    for (int i = 0; i < o.clients; ++i) {
        const int fd = socket(AF_INET, SOCK_STREAM, 0);
        if (fd < 0 || connect(fd, reinterpret_cast<const sockaddr*>(&to), sizeof to) != 0) fail("client connect");
        no_delay(fd);
        epoll_event ev{};
        ev.events = EPOLLIN;
        ev.data.fd = fd;
        epoll_ctl(poll, EPOLL_CTL_ADD, fd, &ev);
        sockets.push_back(fd);
    }
    state.connected = true;
    const std::vector<char> input(static_cast<size_t>(o.input_bytes), 'i');
    std::vector<char> sink(1 << 16);
    std::vector<epoll_event> ready(static_cast<size_t>(o.clients));
    const auto period = std::chrono::duration<double>(1.0 / o.input_hz);
    auto next = clock_type::now();
    while (!state.stop) {
        for (int fd : sockets) send(fd, input.data(), input.size(), MSG_NOSIGNAL);
        next += std::chrono::duration_cast<clock_type::duration>(period);
        for (;;) {
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(next - clock_type::now()).count();
            const int n =
                epoll_wait(poll, ready.data(), static_cast<int>(ready.size()), left > 0 ? static_cast<int>(left) : 0);
            for (int k = 0; k < n; ++k)
                recv(ready[static_cast<size_t>(k)].data.fd, sink.data(), sink.size(), MSG_DONTWAIT);
            if (left <= 0 || state.stop) break;
        }
    }
    for (int fd : sockets) close(fd);
    close(poll);
}

// run_clients on its own thread: a failure (too few file descriptors, say) is reported to the
// server thread instead of ending the process.
void client_thread(const options& o, uint16_t port, client_state& state) {
    try {
        run_clients(o, port, state);
    } catch (const std::exception& e) {
        state.error = e.what();
        state.failed = true;
    }
}

}  // namespace

int main(int argc, char** argv) {
    options o;
    CLI::App app{"The least CPU a TCP server spends on K clients' inputs and snapshots (no game, no framework)"};
    app.add_option("--clients", o.clients, "connections")->check(CLI::Range(1, 20000));
    app.add_option("--seconds", o.seconds, "measured window, s")->check(CLI::Range(1.0, 3600.0));
    app.add_option("--input-bytes", o.input_bytes, "bytes per input message")->check(CLI::Range(1, 65536));
    app.add_option("--snapshot-bytes", o.snapshot_bytes, "bytes per snapshot message")->check(CLI::Range(1, 1 << 20));
    app.add_option("--input-hz", o.input_hz, "inputs per second per client")->check(CLI::Range(1.0, 1000.0));
    app.add_option("--snapshot-hz", o.snapshot_hz, "snapshots per second per client")->check(CLI::Range(1.0, 1000.0));
    app.add_option("--server-cpu", o.server_cpu, "CPU the server thread runs on")->check(CLI::NonNegativeNumber);
    app.add_option("--client-cpu", o.client_cpu, "CPU the client thread runs on")->check(CLI::NonNegativeNumber);
    CLI11_PARSE(app, argc, argv);
    try {
        pin_to(o.server_cpu);
        const int listener = socket(AF_INET, SOCK_STREAM, 0);
        sockaddr_in at{};
        at.sin_family = AF_INET;
        at.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        socklen_t length = sizeof at;
        if (listener < 0 || bind(listener, reinterpret_cast<const sockaddr*>(&at), sizeof at) != 0 ||
            listen(listener, o.clients) != 0 || getsockname(listener, reinterpret_cast<sockaddr*>(&at), &length) != 0)
            fail("listen");
        client_state state;
        std::thread clients(client_thread, std::cref(o), ntohs(at.sin_port), std::ref(state));
        // Joined on every way out, so that a failure is reported, not std::terminate.
        struct joiner {
            std::thread& t;
            client_state& s;
            ~joiner() {
                s.stop = true;
                t.join();
            }
        } join_clients{clients, state};
        const int poll = epoll_create1(0);
        std::vector<int> sockets;
        while (static_cast<int>(sockets.size()) < o.clients) {
            if (state.failed) throw std::runtime_error("clients: " + state.error);
            pollfd waiting{listener, POLLIN, 0};
            if (::poll(&waiting, 1, 100) <= 0) continue;  // a connection, or a look at the clients
            const int fd = accept(listener, nullptr, nullptr);
            if (fd < 0) fail("accept");
            no_delay(fd);
            epoll_event ev{};
            ev.events = EPOLLIN;  // level-triggered: nothing to re-arm after a read
            ev.data.fd = fd;
            epoll_ctl(poll, EPOLL_CTL_ADD, fd, &ev);
            sockets.push_back(fd);
        }
        while (!state.connected) {
            if (state.failed) throw std::runtime_error("clients: " + state.error);
            std::this_thread::yield();
        }

        const std::vector<char> snapshot(static_cast<size_t>(o.snapshot_bytes), 's');
        std::vector<char> buffer(4096);
        std::vector<epoll_event> ready(static_cast<size_t>(o.clients));
        const auto snapshot_period =
            std::chrono::duration_cast<clock_type::duration>(std::chrono::duration<double>(1.0 / o.snapshot_hz));
        const double cpu_start = thread_cpu_seconds();
        const auto start = clock_type::now();
        const auto end =
            start + std::chrono::duration_cast<clock_type::duration>(std::chrono::duration<double>(o.seconds));
        auto next_snapshot = start + snapshot_period;
        uint64_t wakes = 0, recvs = 0, sends = 0, bytes_in = 0;
        for (auto now = start; now < end; now = clock_type::now()) {
            if (now >= next_snapshot) {
                for (int fd : sockets)
                    sends += send(fd, snapshot.data(), snapshot.size(), MSG_DONTWAIT | MSG_NOSIGNAL) > 0;
                next_snapshot += snapshot_period;
                continue;
            }
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(next_snapshot - now).count() + 1;
            const int n = epoll_wait(poll, ready.data(), static_cast<int>(ready.size()), static_cast<int>(left));
            ++wakes;
            for (int k = 0; k < n; ++k) {
                const ssize_t got = recv(ready[static_cast<size_t>(k)].data.fd, buffer.data(), buffer.size(), 0);
                ++recvs;
                if (got > 0) bytes_in += static_cast<uint64_t>(got);
            }
        }
        const double window = std::chrono::duration<double>(clock_type::now() - start).count();
        const double cpu = thread_cpu_seconds() - cpu_start;
        for (int fd : sockets) close(fd);
        close(poll);
        close(listener);
        std::printf(
            "{\"bench\":\"tcp_floor\",\"clients\":%d,\"seconds\":%.2f,\"input_bytes\":%d,\"snapshot_bytes\":%d,"
            "\"inputs_per_s\":%.0f,\"snapshot_sends_per_s\":%.0f,\"recv_calls_per_s\":%.0f,\"epoll_waits_per_s\":%.0f,"
            "\"server_cpu_s_per_s\":%.4f}\n",
            o.clients, window, o.input_bytes, o.snapshot_bytes, static_cast<double>(bytes_in) / o.input_bytes / window,
            static_cast<double>(sends) / window, static_cast<double>(recvs) / window,
            static_cast<double>(wakes) / window, cpu / window);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "arena-bench-tcp-floor: %s\n", e.what());
        return 1;
    }
    return 0;
}
