// Many matches in one process, end to end: arena-server ticking its matches on 8 threads and
// recording each to a folder (--record FOLDER/), arena-bots filling duels by join-or-create, and
// arena-replay re-simulating every recording on one thread with every recorded hash checked
// (docs/MATCHES.md, "Recording every match").
#include <signal.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "common/run_command.hpp"
#include "process.hpp"

using arena::test::child_process;
using arena::test::program;
using arena::test::temp_dir;
using namespace std::chrono_literals;
using nlohmann::json;

TEST_CASE("each match's recording (--record FOLDER, 8 threads) replays on one thread, every hash matching",
          "[e2e][matches][replay]") {
    temp_dir dir;
    std::ofstream(dir.file("modes.json"))
        << R"({"modes": [{"name": "duel", "preset": "asteroids", "max_players": 2}]})";
    const std::string folder = dir.file("recordings/");  // a path ending in '/' is a folder, made if missing
    child_process server(program("arena-server"),
                         {"--bind", "127.0.0.1", "--port", "0", "--modes", dir.file("modes.json"), "--threads", "8",
                          "--record", folder, "--hash-interval", "10", "--stats-json", dir.file("stats.json")},
                         dir.file("server.log"));
    const auto port = arena::test::wait_for_listening(server, 5s);
    REQUIRE(port);
    // Six bots asking for a duel: three matches created on demand, beside the default one.
    child_process bots(program("arena-bots"),
                       {"--host", "127.0.0.1", "--port", std::to_string(*port), "--bots", "6", "--mode", "duel",
                        "--behavior", "mixed", "--duration", "4", "--seed", "5", "--quiet"},
                       dir.file("bots.log"));
    REQUIRE(bots.wait_for(30s) == 0);
    server.signal(SIGTERM);
    REQUIRE(server.wait_for(10s) == 0);

    const json stats = json::parse(std::ifstream(dir.file("stats.json")));
    std::set<std::string> duels;
    for (const json& m : stats.at("matches"))
        if (m.at("mode") == "duel") duels.insert(m.at("id").get<std::string>());
    CHECK(duels.size() == 3);

    std::set<std::string> recorded;
    for (const auto& entry : std::filesystem::directory_iterator(folder)) recorded.insert(entry.path().filename());
    std::set<std::string> expected{"default.arpl"};
    for (const std::string& id : duels) expected.insert(id + ".arpl");
    CHECK(recorded == expected);

    for (const std::string& name : recorded) {
        INFO(name);
        child_process replay(program("arena-replay"), {folder + name}, dir.file(name + ".replay.log"));
        REQUIRE(replay.wait_for(30s) == 0);
        const std::string out = replay.output();
        INFO(out);
        CHECK(out.find("final_hash=") != std::string::npos);
        // A duel ran for the bots' seconds: a few hundred ticks, a hash every 10 of them.
        if (name != "default.arpl") CHECK(out.find("hashes_checked=0\n") == std::string::npos);
    }
}
