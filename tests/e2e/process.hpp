#pragma once
// Child processes for end-to-end tests: arena-server and arena-bots run as real programs.
// Output goes to a file, not a pipe, so that a chatty child never blocks on a full pipe
// while the test waits for something else. A child still running when its object dies is
// killed and reaped: a failed REQUIRE never leaves a server behind.
#include <sys/types.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace arena::test {

// A fresh directory under $TMPDIR (or /tmp), removed with its files on destruction.
class temp_dir {
public:
    temp_dir();
    ~temp_dir();
    temp_dir(const temp_dir&) = delete;
    temp_dir& operator=(const temp_dir&) = delete;
    [[nodiscard]] std::string file(const std::string& name) const { return path_ + "/" + name; }

private:
    std::string path_;
};

class child_process {
public:
    // Starts `program` with `args` (argv[1..]), stdout and stderr appended to `output_file`.
    // Throws std::runtime_error when it cannot be started.
    child_process(const std::string& program, const std::vector<std::string>& args, std::string output_file);
    ~child_process();
    child_process(const child_process&) = delete;
    child_process& operator=(const child_process&) = delete;

    // Its exit code once it exited (128 + signal when killed), or nothing after `timeout`.
    std::optional<int> wait_for(std::chrono::milliseconds timeout);
    void signal(int signo);
    [[nodiscard]] bool running() const { return !exit_code_.has_value(); }
    [[nodiscard]] pid_t pid() const { return pid_; }
    // Resident set size in KiB from /proc (-1 once it has exited).
    [[nodiscard]] long rss_kib() const;
    // Everything it printed so far.
    [[nodiscard]] std::string output() const;

private:
    pid_t pid_ = -1;
    std::string output_file_;
    std::optional<int> exit_code_;
};

// Waits until the server printed "listening on HOST:PORT" and returns PORT, or nothing.
std::optional<unsigned> wait_for_listening(const child_process& server, std::chrono::milliseconds timeout);

// Waits until the output holds a line "PREFIX HOST:PORT" (e.g. "udp listening on") and
// returns PORT, or nothing.
std::optional<unsigned> wait_for_port_line(const child_process& server, const std::string& prefix,
                                           std::chrono::milliseconds timeout);

// Reads a whole file; empty when missing.
std::string read_file(const std::string& path);

}  // namespace arena::test
