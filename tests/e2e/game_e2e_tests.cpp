// Asteroids as a game, end to end: arena-server (--rules asteroids, recording) and 16 hunter
// bots (12 over TCP, 4 over WebSocket) as processes on loopback. The server's --duration ends the match, so every bot
// gets the final scoreboard in the server's Bye; it must equal the server's own (--stats-json) and the recording's
// (arena-replay --scoreboard).
#include <signal.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "process.hpp"

namespace {

using arena::test::child_process;
using arena::test::temp_dir;
using namespace std::chrono_literals;
using nlohmann::json;

const std::string bin_dir = ARENA_BIN_DIR;

// The fields both scoreboards hold, per player id.
json comparable(const json& lines, bool with_names) {
    json out = json::array();
    for (const json& l : lines) {
        json c = {{"player", l.at("player")}, {"score", l.at("score")}, {"kills", l.at("kills")},
                  {"deaths", l.at("deaths")}, {"shots", l.at("shots")}, {"hits", l.at("hits")}};
        if (with_names) c["name"] = l.at("name");
        out.push_back(c);
    }
    return out;
}

}  // namespace

TEST_CASE("16 hunter bots play a match: every client's final scoreboard is the server's and the replay's",
          "[e2e][game]") {
    temp_dir dir;
    // 12 s of play: hunters shoot rocks within a second and each other within a few (16 of
    // them measured 8 kills in 12 s); the server ends the match, not the bots. 12 bots over
    // TCP and 4 over WebSocket: each transport's Bye carries the result.
    child_process server(
        bin_dir + "/arena-server",
        {"--bind", "127.0.0.1", "--port", "0", "--http-port", "0", "--preset", "asteroids", "--rules", "asteroids",
         "--seed", "3", "--duration", "12", "--record", dir.file("match.arpl"), "--stats-json", dir.file("stats.json")},
        dir.file("server.log"));
    const auto port = arena::test::wait_for_listening(server, 5s);
    const auto http_port = arena::test::wait_for_port_line(server, "http listening on", 5s);
    REQUIRE(port);
    REQUIRE(http_port);
    const auto bots = [&](const std::string& name, unsigned on, uint32_t count, const std::string& transport) {
        return std::make_unique<child_process>(
            bin_dir + "/arena-bots",
            std::vector<std::string>{"--host",        "127.0.0.1", "--port",         std::to_string(on),
                                     "--transport",   transport,   "--bots",         std::to_string(count),
                                     "--behavior",    "hunter",    "--duration",     "30",
                                     "--seed",        "4",         "--connect-rate", "100",
                                     "--name-prefix", name,        "--json",         dir.file(name + ".json")},
            dir.file(name + ".log"));
    };
    const std::unique_ptr<child_process> tcp = bots("bot", *port, 12, "tcp");
    const std::unique_ptr<child_process> ws = bots("ws", *http_port, 4, "ws");
    for (child_process* p : {tcp.get(), ws.get()}) {
        const auto code = p->wait_for(40s);
        INFO(p->output());
        REQUIRE(code.has_value());
        CHECK(*code == 0);
    }
    REQUIRE(server.wait_for(10s) == 0);
    INFO(server.output());
    // The text summary prints the scoreboard with accuracy.
    CHECK(tcp->output().find("scoreboard (final, from the server's Bye; winner: ") != std::string::npos);
    CHECK(tcp->output().find("accuracy") != std::string::npos);
    CHECK(tcp->output().find("own shots: ") != std::string::npos);
    CHECK(tcp->output().find("hit registration: ") != std::string::npos);

    const json stats = json::parse(arena::test::read_file(dir.file("stats.json")));
    const json live = comparable(stats.at("scoreboard"), true);
    REQUIRE(live.size() == 16);
    uint64_t shots = 0, hits = 0, kills = 0;
    for (const json& l : live) {
        shots += l.at("shots").get<uint64_t>();
        hits += l.at("hits").get<uint64_t>();
        kills += l.at("kills").get<uint64_t>();
    }
    CHECK(shots > 0);
    CHECK(hits > 0);
    CHECK(kills > 0);
    for (const auto& [name, count] : {std::pair<std::string, uint32_t>{"bot", 12}, {"ws", 4}}) {
        INFO(name);
        const json report = json::parse(arena::test::read_file(dir.file(name + ".json")));
        CHECK(report.at("joined") == count);
        CHECK(report.at("failed") == 0);
        const json& board = report.at("scoreboard");
        CHECK(board.at("final") == true);
        CHECK(board.at("clients") == count);
        CHECK(board.at("agreeing") == count);  // every client saw the same final scoreboard
        CHECK(board.at("game_events").get<uint64_t>() > 0);
        CHECK(board.at("winner") == stats.at("winner"));
        // Own shots predicted and matched to the server's over real sockets. Delta snapshots
        // quantise the ship's state, so the spawns are off by millimetres, not bit-exact
        // (measured over TCP: p50 1.6 mm, p99 2.7 mm; 12 of 806 unconfirmed). The median, as
        // a loaded machine's late inputs (slips) add a few shots a tick of motion off.
        const json& own = report.at("own_shots");
        const uint64_t matched = own.at("exact").get<uint64_t>() + own.at("with_error").get<uint64_t>();
        CHECK(matched > 0);
        CHECK(own.at("unconfirmed").get<uint64_t>() * 20 <= matched);
        CHECK(report.at("figures").at("own_shot_error_m").at("p50").get<double>() < 0.005);
        // Hit registration over loopback: the bots saw hits, and the server confirmed most
        // (client_sim/README.md, "Hit registration"; a short match on a machine that may be
        // slow, under sanitizers: only a loose bound; tests/simnet holds the 95 %).
        const json& reg = report.at("hit_registration");
        CHECK(reg.at("claimed").get<uint64_t>() > 0);
        CHECK(reg.at("confirmed").get<uint64_t>() * 10 >= reg.at("claimed").get<uint64_t>() * 6);
        CHECK(reg.at("confirmed").get<uint64_t>() <= reg.at("claimed").get<uint64_t>());
        // The server's own, line for line, from every client.
        CHECK(comparable(board.at("lines"), true) == live);
        for (const json& seen : report.at("scoreboards")) {
            INFO(seen.at("bot"));
            CHECK(seen.at("final") == true);
            CHECK(comparable(seen.at("lines"), true) == live);
        }
    }

    // The recording replays to the same scoreboard, names included (it held player ids alone).
    child_process replay(bin_dir + "/arena-replay", {dir.file("match.arpl"), "--scoreboard"}, dir.file("replay.log"));
    REQUIRE(replay.wait_for(30s) == 0);
    const std::string out = replay.output();
    const size_t open = out.find('[');
    REQUIRE(open != std::string::npos);
    const json replayed = json::parse(out.substr(open, out.find('\n', open) - open));
    CHECK(comparable(replayed, true) == comparable(stats.at("scoreboard"), true));
}
