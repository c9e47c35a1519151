#pragma once
// Runs a shell command as a user would and collects what it printed: the tests of every
// program (arena-sim, arena-replay, arena-token, promtool) go through this one helper.
#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace arena::test {

struct command_result {
    int exit_code = -1;  // -1 when it did not exit normally (a signal)
    std::string output;  // stdout, plus whatever the command's own redirects send there
};

inline command_result run_command(const std::string& command) {
    command_result r;
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) return r;
    char chunk[4096];
    while (size_t n = std::fread(chunk, 1, sizeof chunk, pipe)) r.output.append(chunk, n);
    const int status = ::pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

// An Arena program from this build: ARENA_BIN_DIR/name.
inline std::string program(const std::string& name) {
    return std::string(ARENA_BIN_DIR) + "/" + name;
}

}  // namespace arena::test
