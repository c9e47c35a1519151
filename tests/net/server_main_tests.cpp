// arena-server's command line and signals (server/server_main.cpp, server/cli/): every
// numeric flag that a conversion could overflow is bounded, and SIGPIPE, SIGHUP and SIGUSR1
// end a match in order instead of killing it.
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <fstream>
#include <regex>
#include <sstream>

#include "common/run_command.hpp"
#include "games/registry.hpp"
#include "protocol/decode.hpp"
#include "protocol/game.hpp"
#include "protocol/version.hpp"
#include "server/config/config_json.hpp"
#include "server_process.hpp"

using namespace arena;
using namespace arena::test;
using namespace std::chrono_literals;
using protocol::Payload;

namespace {

// arena-server with `args`, bounded in time whatever it does with them.
command_result server_run(const std::string& args) {
    return run_command("timeout 20 " + program("arena-server") + " --port 0 " + args + " 2>&1");
}

// The game's part of the next snapshot `client` reads: the scoreboard lines, names, events.
protocol::game_list next_game(test_client& client) {
    const auto frame = client.read_until(Payload::Snapshot);
    REQUIRE(frame);
    const auto snapshot = protocol::decode_snapshot(*message_of(*frame));
    REQUIRE(snapshot);
    protocol::game_list game;
    REQUIRE(protocol::read_game(*snapshot.value.table, game).empty());
    return game;
}

}  // namespace

TEST_CASE("arena-server refuses numeric flags that would overflow, naming the flag", "[net][cli]") {
    // Each of these was accepted and then wrapped: --stall-timeout 1e10 dropped every client,
    // --handshake-timeout 1e10 refused every connection, --duration 1e10 ended the match at
    // tick 0, --reconnect-grace 71582789 became 44 ticks.
    const std::pair<const char*, const char*> cases[] = {
        {"--stall-timeout", "1e10"}, {"--handshake-timeout", "1e10"},
        {"--duration", "1e10"},      {"--reconnect-grace", "71582789"},
        {"--drain-grace", "1e10"},   {"--stats-interval", "1e300"},
        {"--view-radius", "1e300"},  {"--agones-shutdown-timeout", "1e10"},
        {"--stall-timeout", "inf"},  {"--duration", "nan"},
        {"--reconnect-grace", "-1"}, {"--idle-timeout", "1e10"},
        {"--idle-timeout", "-1"},
    };
    for (const auto& [flag, value] : cases) {
        INFO(flag << " " << value);
        // --duration 0.2: should the flag be accepted, the server stops by itself.
        const std::string duration = std::string(flag) == "--duration" ? "" : " --duration 0.2";
        const auto r = server_run(std::string(flag) + " " + value + duration);
        CHECK(r.exit_code == 2);
        CHECK(r.output.rfind(std::string("arena-server: ") + flag + ": ", 0) == 0);
        CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
    }
}

TEST_CASE("arena-server takes its flags at their upper bounds without wrapping", "[net][cli]") {
    const std::string stats = temp_path("bounds-stats.json");
    const auto r = server_run(
        "--stall-timeout 3600 --handshake-timeout 3600 --idle-timeout 3600 --reconnect-grace 3600 --drain-grace 60 "
        "--view-radius 1e7 --duration 0.3 --stats-json " +
        stats);
    CHECK(r.exit_code == 0);
    const std::string text = read_file(stats);
    CHECK(text.find("\"stall_timeout_s\": 3600.0") != std::string::npos);
    CHECK(text.find("\"handshake_timeout_s\": 3600.0") != std::string::npos);
    CHECK(text.find("\"idle_timeout_s\": 3600.0") != std::string::npos);
    std::remove(stats.c_str());
}

TEST_CASE("a snapshot rate that does not divide the tick rate is refused, so the Welcome tells the truth",
          "[net][cli]") {
    // Asking for 50 at 60 Hz used to give 60 snapshots a second, and 7 gave 7.5, while the
    // Welcome said 50 and 7.
    for (const char* args : {"--snapshot-rate 50", "--snapshot-rate 7", "--tick-rate 30 --snapshot-rate 20"}) {
        INFO(args);
        const auto r = server_run(std::string(args) + " --duration 0.2");
        CHECK(r.exit_code == 2);
        CHECK(r.output.rfind("arena-server: --snapshot-rate: ", 0) == 0);
        CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
    }
    CHECK(server_run("--snapshot-rate 30 --duration 0.2").exit_code == 0);
}

TEST_CASE("arena-server --rules names the game the match plays, and an unknown name is refused in one line",
          "[net][cli]") {
    const auto r = server_run("--rules chess --duration 0.2");
    CHECK(r.exit_code == 2);
    CHECK(r.output == "arena-server: --rules: unknown rules 'chess' (" + games::names_list() + ")\n");
    // With the Asteroids rules a player's snapshots carry its scoreboard line: three lives.
    server_process server({"--preset", "asteroids", "--rules", "asteroids"});
    test_client client(server.port());
    client.send_frame(protocol::encode_hello(protocol::protocol_version, "ada", ""));
    REQUIRE(client.read_until(Payload::Welcome));
    const protocol::game_list game = next_game(client);
    REQUIRE(game.players.size() == 1);
    CHECK(game.players[0].lives == 3);
    CHECK(game.names == std::vector<std::string>{"ada"});
    CHECK(server.stop(SIGTERM) == 0);
}

TEST_CASE("a config's rules_params reach the match and the Welcome, and bad ones stop the server in one line",
          "[net][cli][params]") {
    const std::string file = temp_path("params.json");
    std::ofstream(file) << R"({"preset": "asteroids", "rules": "asteroids", "rules_params": {"lives": 7}})";
    server_process server({"--config", file});
    test_client client(server.port());
    client.send_frame(protocol::encode_hello(protocol::protocol_version, "ada", ""));
    const auto welcome_frame = client.read_until(Payload::Welcome);
    REQUIRE(welcome_frame);
    const auto welcome = protocol::decode_welcome(*message_of(*welcome_frame));
    REQUIRE(welcome);
    const auto sent = config::parse_config_json(welcome.value.world_config);
    REQUIRE(sent);
    CHECK(sent.value.rules_params == R"({"lives":7})");
    const protocol::game_list game = next_game(client);
    REQUIRE(game.players.size() == 1);
    CHECK(game.players[0].lives == 7);
    CHECK(server.stop(SIGTERM) == 0);

    std::ofstream(file) << R"({"preset": "asteroids", "rules": "asteroids", "rules_params": {"lifes": 7}})";
    const auto r = server_run("--config " + file + " --duration 0.2");
    CHECK(r.exit_code == 2);
    CHECK(r.output == "arena-server: " + file + ": unknown field rules_params.lifes\n");
}

TEST_CASE("arena-server --preset asteroids plays the asteroids rules without --rules", "[net][cli]") {
    // It played the sandbox's: rocks, but no bullets, score or scoreboard in the snapshots.
    server_process server({"--preset", "asteroids"});
    test_client client(server.port());
    client.send_frame(protocol::encode_hello(protocol::protocol_version, "ada", ""));
    REQUIRE(client.read_until(Payload::Welcome));
    const protocol::game_list game = next_game(client);
    REQUIRE(game.players.size() == 1);
    CHECK(game.players[0].lives == 3);
    CHECK(server.stop(SIGTERM) == 0);
}

TEST_CASE("a --record file or folder that cannot be made stops the server in one line", "[net][cli][replay]") {
    // A file in a folder that does not exist: the recorder's own message.
    const auto file = server_run("--record /nonexistent-arena-folder/x.arpl --duration 0.2");
    CHECK(file.exit_code == 2);
    CHECK(file.output ==
          "arena-server: --record: /nonexistent-arena-folder/x.arpl: cannot create the replay file: No "
          "such file or directory\n");
    // A folder (a path ending in '/') under one that cannot hold folders.
    const auto folder = server_run("--record /proc/arena-recordings/ --duration 0.2");
    CHECK(folder.exit_code == 2);
    CHECK(folder.output.rfind("arena-server: --record: cannot create the folder /proc/arena-recordings/: ", 0) == 0);
    CHECK(std::count(folder.output.begin(), folder.output.end(), '\n') == 1);
}

TEST_CASE("SIGHUP ends the match like SIGTERM: Bye, stats and a finished recording", "[net][e2e][signal]") {
    const std::string stats = temp_path("hup-stats.json"), recording = temp_path("hup.arpl");
    server_process server({"--stats-json", stats, "--record", recording});
    test_client client(server.port());
    client.send_frame(protocol::encode_hello(protocol::protocol_version, "hup", ""));
    REQUIRE(client.read_until(Payload::Welcome));
    REQUIRE(client.read_until(Payload::Snapshot));
    ::kill(server.pid(), SIGHUP);
    auto bye = client.read_until(Payload::Bye);
    REQUIRE(bye);
    CHECK(protocol::decode_bye(*message_of(*bye)).value.reason.find("SIGHUP") != std::string::npos);
    CHECK(server.stop(0) == 0);
    CHECK(read_file(stats).find("\"joins\": 1") != std::string::npos);
    const auto replayed = run_command(program("arena-replay") + " " + recording + " 2>&1");
    INFO(replayed.output);
    CHECK(replayed.exit_code == 0);
    std::remove(stats.c_str());
    std::remove(recording.c_str());
}

TEST_CASE("SIGUSR1 ends the match like SIGTERM: Bye, stats and a finished recording", "[net][e2e][signal]") {
    // SIGUSR1's default action killed the server at once: no Bye, no --stats-json, a recording
    // without its end. It is one of the signals the host ends a run on, in order.
    const std::string stats = temp_path("usr1-stats.json"), recording = temp_path("usr1.arpl");
    server_process server({"--stats-json", stats, "--record", recording});
    test_client client(server.port());
    client.send_frame(protocol::encode_hello(protocol::protocol_version, "usr1", ""));
    REQUIRE(client.read_until(Payload::Welcome));
    REQUIRE(client.read_until(Payload::Snapshot));
    ::kill(server.pid(), SIGUSR1);
    auto bye = client.read_until(Payload::Bye);
    REQUIRE(bye);
    CHECK(protocol::decode_bye(*message_of(*bye)).value.reason.find("SIGUSR1") != std::string::npos);
    CHECK(server.stop(0) == 0);
    CHECK(read_file(stats).find("\"joins\": 1") != std::string::npos);
    const auto replayed = run_command(program("arena-replay") + " " + recording + " 2>&1");
    INFO(replayed.output);
    CHECK(replayed.exit_code == 0);
    std::remove(stats.c_str());
    std::remove(recording.c_str());
}

TEST_CASE("a log reader that goes away (SIGPIPE) does not kill the server", "[net][e2e][signal]") {
    // `arena-server ... 2>&1 | head -2`: once head exits, every log line is a write to a
    // closed pipe. The server's own exit status comes back through PIPESTATUS.
    const std::string stats = temp_path("pipe-stats.json");
    const auto r = run_command("bash -c 'timeout 20 " + program("arena-server") +
                               " --port 0 --duration 1 --stats-interval 0.05 --stats-json " + stats +
                               " 2>&1 | head -2 >/dev/null; echo \"${PIPESTATUS[0]}\"'");
    CHECK(r.output == "0\n");
    CHECK(read_file(stats).find("\"ticks\"") != std::string::npos);
    std::remove(stats.c_str());
}

TEST_CASE("the periodic stats log line keeps its fields, their order and their format", "[net][e2e][stats]") {
    // Scripts read this line: it is rendered from the report()s (server/ops/stats_line.hpp) and
    // must stay the line it always was.
    const auto r = run_command("timeout 20 " + program("arena-server") +
                               " --port 0 --duration 0.6 --stats-interval 0.2 2>&1 >/dev/null");
    const std::regex line(
        R"(\[ *[0-9.]+\] stats players=0 spectators=0 ticks=[0-9]+ tick_ms_p50=[0-9]+\.[0-9]{3} tick_ms_p99=[0-9]+\.[0-9]{3} )"
        R"(tick_ms_max=[0-9]+\.[0-9]{3} overruns=[0-9]+ bytes_in_per_s=[0-9]+ bytes_out_per_s=[0-9]+ connections=0)");
    std::istringstream lines(r.output);
    int found = 0;
    for (std::string l; std::getline(lines, l);)
        if (l.find("stats ") != std::string::npos) {
            INFO(l);
            CHECK(std::regex_match(l, line));
            ++found;
        }
    CHECK(found >= 2);
}
