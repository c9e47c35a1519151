// A recording names its players: a session of named players through the match, recorded as
// arena-server records it, replays to the live scoreboard, names included (a recording held
// player ids alone, so arena-replay --scoreboard showed "" where the live one showed names).
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "match/drive.hpp"
#include "replay_files.hpp"
#include "server/config/scoreboard_json.hpp"
#include "server/match/match.hpp"
#include "server/replay/recorder.hpp"
#include "server/replay/replayer.hpp"
#include "server/world/presets.hpp"

using namespace arena;
using namespace arena::match_test;
using arena::replay::testing::temp_file;

namespace {

std::string live_scoreboard(const match::match& m) {
    std::vector<rules::score_line> lines;
    std::vector<std::string> names;
    for (const match::match::named_score& s : m.scoreboard()) {
        lines.push_back(s.line);
        names.push_back(s.name);
    }
    return config::scoreboard_json(lines, names);
}

}  // namespace

TEST_CASE("a recorded session of named players replays to the live scoreboard, names included", "[replay][names]") {
    temp_file file("named_session");
    world::world_config world = world::asteroids_preset();
    world.rules = "asteroids";
    match::match_config config;
    match::match m(config, world);
    auto opened =
        replay::recorder::open(file.path(), replay::make_header(m.state(), "asteroids", config.seed, config.tick_rate));
    REQUIRE(opened.ok());
    replay::recorder rec = std::move(opened.value);
    m.on_tick = [&](const match::tick_record& r, uint64_t hash) {
        REQUIRE(rec.record_tick(r, hash).ok());
    };

    // Two players join in one tick, a spectator watches, a third player joins later and leaves.
    quiet_client ada("10.0.0.1:1"), bob("10.0.0.2:1"), eve("10.0.0.3:1"), cyd("10.0.0.4:1");
    const protocol::hello_msg hello{protocol::protocol_version, "ada", "", true, false};
    REQUIRE(join(m, ada, hello) != 0);
    REQUIRE(join(m, bob, {protocol::protocol_version, "Bob \xc3\xa9", "", true, false}) != 0);
    REQUIRE(join(m, eve, {protocol::protocol_version, "eve", "", true, true}) != 0);
    for (uint32_t k = 1; k <= 240; ++k) {
        if (k == 60) REQUIRE(join(m, cyd, {protocol::protocol_version, "cyd", "", true, false}) != 0);
        if (k == 200) say_bye(m, cyd);
        // Both fire and turn: shots, and hits on the rocks, for the scoreboard to hold.
        for (quiet_client* c : {&ada, &bob}) {
            protocol::input_msg in;
            in.sequence = k;
            in.thrust = 0.3f;
            in.turn = c == &ada ? 0.5f : -0.5f;
            in.buttons = world::button_impulse;
            CHECK(send_input(m, *c, in));
        }
        m.tick();
    }
    REQUIRE(rec.finish(m.state().tick(), rules::state_hash(m.state(), m.game_rules())).ok());
    const std::string live = live_scoreboard(m);
    CHECK(live.find("\"name\":\"ada\"") != std::string::npos);
    CHECK(live.find("\"name\":\"cyd\"") != std::string::npos);

    auto replayed = replay::replayer::open(file.path());
    REQUIRE(replayed.ok());
    const replay::replay_report report = replayed.value->run();
    INFO(report.error);
    REQUIRE(report.complete);
    const std::vector<rules::score_line> lines = replayed.value->game_rules().scoreboard();
    CHECK(config::scoreboard_json(lines, replayed.value->scoreboard_names(lines)) == live);
}
