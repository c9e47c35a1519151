// Accept loops out of file descriptors: the backoff on its own with a clock the test sets, then
// the ops endpoint in a child process whose descriptor limit is used up.
#include <catch2/catch.hpp>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>
#include <cerrno>
#include <vector>

#include "server/ops/accept_backoff.hpp"
#include "server/ops/http_server.hpp"
#include "tests/common/descriptors.hpp"
#include "tests/ops/loopback.hpp"

using namespace arena::ops;

namespace {

const boost::system::error_code emfile(EMFILE, boost::system::system_category());
const boost::system::error_code enfile(ENFILE, boost::system::system_category());
const boost::system::error_code aborted(ECONNABORTED, boost::system::system_category());
constexpr int64_t ms = 1'000'000;

}  // namespace

TEST_CASE("accept backoff: out of descriptors, pauses double to the cap and reset after an accept", "[ops][accept]") {
    accept_backoff b("test", {});
    CHECK(b.failed(emfile, 0) == 10 * ms);
    CHECK(b.failed(emfile, 10 * ms) == 20 * ms);
    CHECK(b.failed(enfile, 30 * ms) == 40 * ms);
    int64_t wait = 0;
    for (int i = 0; i < 20; ++i) wait = b.failed(emfile, 100 * ms * i);
    CHECK(wait == 1000 * ms);
    b.succeeded();
    CHECK(b.failed(emfile, 5000 * ms) == 10 * ms);
    // One connection's trouble is no reason to stop taking the others.
    CHECK(b.failed(aborted, 5001 * ms) == 0);
    CHECK(out_of_resources(emfile));
    CHECK(out_of_resources(boost::system::error_code(ENOBUFS, boost::system::system_category())));
    CHECK_FALSE(out_of_resources(aborted));
    CHECK_FALSE(out_of_resources(boost::asio::error::operation_aborted));
}

TEST_CASE("accept backoff: a million errors in 30 s log three lines, each counting the ones it skipped",
          "[ops][accept]") {
    std::vector<std::string> lines;
    accept_backoff b("game", [&](const std::string& line) { lines.push_back(line); });
    for (int64_t i = 0; i < 1'000'000; ++i) b.failed(emfile, i * 30'000);  // one per 30 µs
    CHECK(b.errors() == 1'000'000);
    REQUIRE(lines.size() == 3);  // at 0, 10 s and 20 s (the run ends just before 30 s)
    CHECK(b.log_lines() == 3);
    CHECK(lines[0] == "game: accept failed: Too many open files; pausing accepts for 10 ms");
    CHECK(lines[1].find("game: accept failed: Too many open files (333334 errors since the last line)") == 0);
    CHECK(lines[1].find("pausing accepts for 1000 ms") != std::string::npos);
    b.failed(emfile, 31'000 * ms);
    CHECK(lines.size() == 4);
}

TEST_CASE("ops http: out of file descriptors, the endpoint pauses its accepts instead of spinning, then recovers",
          "[ops][accept]") {
    // A child process, so that its descriptor limit and the descriptors it uses up are its own.
    int ports[2], results[2];
    REQUIRE(pipe(ports) == 0);
    REQUIRE(pipe(results) == 0);
    const pid_t child = fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        arena::test::close_inherited_descriptors({ports[1], results[1]});
        rlimit limit{64, 64};
        if (setrlimit(RLIMIT_NOFILE, &limit) != 0) _exit(3);
        uint64_t lines = 0;
        boost::asio::io_context io;
        http_server server(io, {},
                           http_handlers{[] { return std::string("m 1\n"); },
                                         [] {
                                             return true;
                                         }},
                           [&lines](const std::string&) { ++lines; });
        server.start();
        std::vector<int> filler;
        for (int fd; (fd = open("/dev/null", O_RDONLY | O_CLOEXEC)) >= 0;) filler.push_back(fd);
        if (errno != EMFILE) _exit(4);
        const uint16_t port = server.port();
        if (write(ports[1], &port, sizeof port) != sizeof port) _exit(5);
        // 1.5 s with every descriptor taken while the parent's connections wait in the queue.
        rusage before{}, after{};
        getrusage(RUSAGE_SELF, &before);
        io.run_for(std::chrono::milliseconds(1500));
        getrusage(RUSAGE_SELF, &after);
        const auto cpu_us = [](const rusage& r) {
            return (r.ru_utime.tv_sec + r.ru_stime.tv_sec) * 1'000'000L + r.ru_utime.tv_usec + r.ru_stime.tv_usec;
        };
        const uint64_t report[3] = {server.accept_errors(), lines,
                                    static_cast<uint64_t>(cpu_us(after) - cpu_us(before))};
        for (int fd : filler) close(fd);
        if (write(results[1], report, sizeof report) != sizeof report) _exit(6);
        // Descriptors are back: serve the parent's probe.
        io.run_for(std::chrono::milliseconds(3000));
        _exit(0);
    }
    close(ports[1]);
    close(results[1]);
    uint16_t port = 0;
    REQUIRE(read(ports[0], &port, sizeof port) == sizeof port);
    std::vector<int> queued;
    for (int i = 0; i < 3; ++i) queued.push_back(arena::test::open_idle_connection(port));
    uint64_t report[3] = {};
    REQUIRE(read(results[0], report, sizeof report) == sizeof report);
    const auto [errors, lines, cpu_us] = report;
    INFO("accept errors " << errors << ", log lines " << lines << ", cpu " << cpu_us << " us");
    WARN("out of descriptors for 1.5 s: " << errors << " accept errors, " << lines << " log lines, " << cpu_us
                                          << " us of CPU");
    // Retrying at once made millions of attempts and lines, at 100 % of a core.
    CHECK(errors >= 3);
    CHECK(errors <= 20);  // 10, 20, 40, ... 640 ms: about 8 pauses in 1.5 s
    CHECK(lines <= 2);
    CHECK(cpu_us < 300'000);
    // Accepting again once descriptors are free: the probe is answered.
    CHECK(arena::test::status_of(arena::test::http_get(port, "/healthz")) == 200);
    for (int fd : queued) close(fd);
    int status = 0;
    waitpid(child, &status, 0);
    CHECK(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 0);
    close(ports[0]);
    close(results[0]);
}
