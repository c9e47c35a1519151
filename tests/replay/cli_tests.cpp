// The built arena-replay, run as a user runs it: exit codes and output lines.
#include <catch2/catch.hpp>

#include "common/run_command.hpp"

#include <sys/wait.h>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "replay_files.hpp"
#include "scripted_session.hpp"

using namespace arena::replay;

namespace {

struct run_result {
    int exit_code = -1;
    std::string out;  // what the chosen streams printed
};

enum class streams { out, err, both };

// Runs arena-replay with `args` (already shell-quoted where needed).
run_result run_replay(const std::string& args, streams which = streams::out) {
    const char* redirect = which == streams::out   ? " 2>/dev/null"
                           : which == streams::err ? " 2>&1 >/dev/null"
                                                   : " 2>&1";
    const auto done = arena::test::run_command(arena::test::program("arena-replay") + " " + args + redirect);
    return {done.exit_code, done.output};
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

const std::string golden_hash = "308927a346773945";

}  // namespace

TEST_CASE("arena-replay replays the golden file, prints its summary and exits 0", "[replay][cli]") {
    const run_result r = run_replay(testing::golden_path());
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.out, Catch::Contains("ticks_replayed=600\n"));
    CHECK_THAT(r.out, Catch::Contains("hashes_checked=12\n"));
    CHECK_THAT(r.out, Catch::Contains("final_hash=" + golden_hash + "\n"));
    CHECK_THAT(r.out, Catch::Contains("ticks_per_second="));
}

TEST_CASE("arena-replay --dump-hashes prints tick,hash for every tick, the same on every run", "[replay][cli]") {
    const run_result first = run_replay("--dump-hashes " + testing::golden_path());
    const run_result second = run_replay("--dump-hashes " + testing::golden_path());
    CHECK(first.exit_code == 0);
    const auto lines = lines_of(first.out);
    REQUIRE(lines.size() == 1 + 601);  // the header, then ticks 0 to 600
    CHECK(lines[0] == "tick,hash");
    CHECK(lines[1].rfind("0,", 0) == 0);
    CHECK(lines.back() == "600," + golden_hash);
    CHECK(first.out == second.out);
}

TEST_CASE("arena-replay --until --state prints every body at that tick", "[replay][cli]") {
    const run_result r = run_replay("--until 131 --state " + testing::golden_path());
    CHECK(r.exit_code == 0);
    const auto lines = lines_of(r.out);
    REQUIRE(lines.size() > 40);
    CHECK(lines[0] == "id,owner,x,y,vx,vy,angle,omega,mass,radius,impulse_cooldown");
    // 40 rocks and the four players present at tick 131: owner 4 joined in the step from 130.
    CHECK(lines.size() == 1 + 40 + 4);
    CHECK_THAT(lines.back(), Catch::StartsWith("44,4,"));
}

TEST_CASE("arena-replay exits 1 naming the tick of the first mismatch", "[replay][cli]") {
    testing::temp_file file("cli_mismatch");
    testing::session_script script;
    script.alter_hash_at = 240;
    const auto recorded = testing::record_scripted_session(file.path(), script);
    REQUIRE(recorded.ok());
    const run_result r = run_replay(file.path(), streams::err);
    CHECK(r.exit_code == 1);
    char expected[128];
    std::snprintf(expected, sizeof expected, ": tick 240: hash mismatch: expected %016llx, actual %016llx",
                  static_cast<unsigned long long>(recorded.value.hashes[240] ^ 1),
                  static_cast<unsigned long long>(recorded.value.hashes[240]));
    CHECK_THAT(r.out, Catch::Contains(expected));
}

TEST_CASE("arena-replay exits 2 with one line naming the offset for a damaged file", "[replay][cli]") {
    testing::temp_file file("cli_damaged");
    std::vector<uint8_t> bytes = testing::read_bytes(testing::golden_path());
    const auto offsets = testing::record_offsets(bytes);
    bytes[offsets[10] + 20] ^= 0xff;
    testing::write_bytes(file.path(), bytes);
    const run_result r = run_replay(file.path(), streams::err);
    CHECK(r.exit_code == 2);
    const auto lines = lines_of(r.out);
    REQUIRE(lines.size() == 1);
    CHECK_THAT(lines[0], Catch::StartsWith("arena-replay: " + file.path() + ": byte offset " +
                                           std::to_string(offsets[10]) + ": checksum mismatch"));
}

TEST_CASE("arena-replay exits 2 on usage errors and missing files", "[replay][cli]") {
    CHECK(run_replay("").exit_code == 2);
    CHECK(run_replay("--no-such-flag " + testing::golden_path()).exit_code == 2);
    CHECK(run_replay("/nonexistent/file.arpl").exit_code == 2);
    CHECK(run_replay("--until 601 " + testing::golden_path()).exit_code == 2);
    CHECK(run_replay("--help").exit_code == 0);
}
