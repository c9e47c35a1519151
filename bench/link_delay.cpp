// arena-link-delay: a point-to-point link between two network namespaces that holds every IP
// packet for a fixed time, in the kernel's packet path, for make bench-loss's added latency.
//
// netem does not exist on these machines, and a delay added inside a client (arena-bots
// --simulate-latency) is invisible to the kernel: a TCP sender's retransmission timer would
// still see the loopback's microsecond round trip and resend a lost segment far sooner than
// it would over a real path. Here each namespace has a TUN device; this program reads the
// packets one side's kernel routes into its device and writes them into the other side's
// device `--delay-ms` later, so both TCP and ENet measure the longer round trip themselves.
//
// Run it inside the first namespace (ip netns exec A arena-link-delay ...). Both devices must
// exist already as persistent TUN devices without packet information (`ip -n A tuntap add dev
// NAME mode tun`), with their addresses and routes set up by the caller. It forwards until
// SIGTERM or SIGINT, then prints what it forwarded on stderr.
//
// `--jitter-ms J` spreads each packet's hold uniformly over delay ± J, keeping the order (a
// packet is never written before one read earlier: a link's queue, not a reordering path).
#include <fcntl.h>
#include <linux/if.h>
#include <linux/if_tun.h>
#include <poll.h>
#include <sched.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <deque>
#include <random>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace {

using time_ns = std::int64_t;

time_ns monotonic_now() {
    timespec t{};
    clock_gettime(CLOCK_MONOTONIC, &t);
    return time_ns{t.tv_sec} * 1'000'000'000 + t.tv_nsec;
}

volatile std::sig_atomic_t stop_requested = 0;
void request_stop(int) {
    stop_requested = 1;
}

// Opens the TUN device `name` of the calling thread's network namespace, non-blocking.
int open_tun(const std::string& name, const char* where) {
    const int fd = open("/dev/net/tun", O_RDWR | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        std::fprintf(stderr, "arena-link-delay: %s: /dev/net/tun: %s\n", where, std::strerror(errno));
        return -1;
    }
    ifreq request{};
    request.ifr_flags = IFF_TUN | IFF_NO_PI;
    std::snprintf(request.ifr_name, IFNAMSIZ, "%s", name.c_str());
    if (ioctl(fd, TUNSETIFF, &request) < 0) {
        std::fprintf(stderr, "arena-link-delay: %s: device %s: %s\n", where, name.c_str(), std::strerror(errno));
        close(fd);
        return -1;
    }
    return fd;
}

// One direction of the link: packets read from `from`, due to be written to `to`.
struct direction {
    int from = -1;
    int to = -1;
    struct held {
        time_ns due = 0;
        std::vector<std::uint8_t> bytes;
    };
    std::deque<held> queue;  // in arrival order, and in due order (read_all keeps it)
    std::uint64_t forwarded = 0;
    std::uint64_t overflowed = 0;  // dropped because the queue was full
};

// A bound on what one direction holds: far above what a benchmark's few hundred KB/s keep in
// flight for a second, and a cap on memory if something floods the link.
constexpr std::size_t max_held_packets = 100'000;
constexpr std::size_t max_packet_bytes = 65'536;

// The spread of each packet's hold (± ns, uniform), from a fixed seed: the same run twice.
struct jitter {
    time_ns spread = 0;
    std::mt19937_64 rng{0x6a697474};
    time_ns next() {
        if (spread == 0) return 0;
        return std::uniform_int_distribution<time_ns>(-spread, spread)(rng);
    }
};

void read_all(direction& d, time_ns delay, jitter& j, std::vector<std::uint8_t>& buffer) {
    for (;;) {
        const ssize_t n = read(d.from, buffer.data(), buffer.size());
        if (n <= 0) return;  // EAGAIN: nothing more for now
        if (d.queue.size() >= max_held_packets) {
            ++d.overflowed;
            continue;
        }
        time_ns due = monotonic_now() + std::max<time_ns>(0, delay + j.next());
        if (!d.queue.empty()) due = std::max(due, d.queue.back().due);  // in order
        d.queue.push_back({due, {buffer.begin(), buffer.begin() + n}});
    }
}

void write_due(direction& d, time_ns now) {
    while (!d.queue.empty() && d.queue.front().due <= now) {
        const auto& packet = d.queue.front().bytes;
        // A full device queue drops the packet, as a congested link would.
        if (write(d.to, packet.data(), packet.size()) == static_cast<ssize_t>(packet.size())) ++d.forwarded;
        d.queue.pop_front();
    }
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"arena-link-delay: a TUN link between two network namespaces that delays every packet"};
    std::string device = "arena0";
    std::string peer_netns;
    double delay_ms = 0;
    app.add_option("--device", device, "the TUN device's name, in both namespaces")->capture_default_str();
    app.add_option("--peer-netns", peer_netns, "the other namespace (ip netns name)")->required();
    app.add_option("--delay-ms", delay_ms, "ms every packet is held, each way")
        ->check(CLI::Range(0.0, 10000.0))
        ->capture_default_str();
    double jitter_ms = 0;
    app.add_option("--jitter-ms", jitter_ms, "ms each packet's hold varies by, ± (uniform), each way; order kept")
        ->check(CLI::Range(0.0, 10000.0))
        ->capture_default_str();
    CLI11_PARSE(app, argc, argv);

    const int here = open_tun(device, "this namespace");
    if (here < 0) return 1;
    const std::string peer_path = "/run/netns/" + peer_netns;
    const int peer_ns = open(peer_path.c_str(), O_RDONLY | O_CLOEXEC);
    if (peer_ns < 0 || setns(peer_ns, CLONE_NEWNET) < 0) {
        std::fprintf(stderr, "arena-link-delay: namespace %s: %s\n", peer_netns.c_str(), std::strerror(errno));
        return 1;
    }
    const int there = open_tun(device, peer_netns.c_str());
    if (there < 0) return 1;

    std::signal(SIGTERM, request_stop);
    std::signal(SIGINT, request_stop);
    const auto delay = static_cast<time_ns>(delay_ms * 1e6);
    direction out;
    out.from = here;
    out.to = there;
    direction back;
    back.from = there;
    back.to = here;
    jitter spread;
    spread.spread = static_cast<time_ns>(jitter_ms * 1e6);
    std::vector<std::uint8_t> buffer(max_packet_bytes);  // one packet read at a time
    std::printf("link-delay ready: %s, %.1f ms each way, ± %.1f ms\n", device.c_str(), delay_ms, jitter_ms);
    std::fflush(stdout);

    while (!stop_requested) {
        pollfd fds[2] = {{here, POLLIN, 0}, {there, POLLIN, 0}};
        // Sleep until a packet comes in or the earliest held one is due.
        time_ns wait = 1'000'000'000;
        const time_ns now = monotonic_now();
        for (const direction* d : {&out, &back})
            if (!d->queue.empty()) wait = std::min(wait, std::max<time_ns>(0, d->queue.front().due - now));
        const timespec timeout{static_cast<time_t>(wait / 1'000'000'000), static_cast<long>(wait % 1'000'000'000)};
        if (ppoll(fds, 2, &timeout, nullptr) < 0 && errno != EINTR) {
            std::fprintf(stderr, "arena-link-delay: poll: %s\n", std::strerror(errno));
            return 1;
        }
        if (fds[0].revents & POLLIN) read_all(out, delay, spread, buffer);
        if (fds[1].revents & POLLIN) read_all(back, delay, spread, buffer);
        const time_ns after = monotonic_now();
        write_due(out, after);
        write_due(back, after);
    }
    std::fprintf(stderr, "arena-link-delay: forwarded %llu and %llu packets; %llu dropped on a full queue\n",
                 static_cast<unsigned long long>(out.forwarded), static_cast<unsigned long long>(back.forwarded),
                 static_cast<unsigned long long>(out.overflowed + back.overflowed));
    return 0;
}
