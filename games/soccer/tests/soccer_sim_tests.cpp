// Soccer as clients hear it over lossy datagrams: the manifest in the Welcome, every player's
// team, goals and kicks and every team's goals as the server had them, and the match's end from
// the rules' clock, with the teams' result in the last Bye.
#include <catch2/catch.hpp>

#include "games/soccer/soccer_pitch.hpp"
#include "games/soccer/soccer_rules.hpp"
#include "simnet/match_sim.hpp"

using namespace arena;
using namespace arena::simnet;

TEST_CASE("soccer's declared state reaches every client over lossy datagrams, and its clock ends the match",
          "[soccer][simnet][manifest]") {
    sim_options o;
    o.kind = link_kind::datagram;
    o.clients = 6;
    o.delta_snapshots = true;
    o.behavior = bots::behavior_choice::seek;
    o.seed = 5;
    o.up.latency = o.down.latency = 60 * ms;
    o.up.loss = o.down.loss = 0.1;
    match::match_config config;
    config.preset = "soccer";
    config.admission.max_players = 6;
    world::world_config world = rules::soccer_pitch();
    world.rules_params = R"({"match_seconds":20})";
    match_sim sim(config, world, o);

    std::map<uint32_t, std::vector<rules::score_line>> boards;  // by tick
    while (!sim.match().over() && sim.match().state().tick() < 1300) {
        sim.run_ticks(1);
        boards[sim.match().state().tick()] = sim.match().game_rules().scoreboard();
    }
    REQUIRE(sim.match().over());
    const protocol::game_manifest manifest = sim.match().game_rules().manifest();
    REQUIRE(manifest.player_fields.size() == 3);
    for (size_t i = 0; i < sim.size(); ++i) {
        const bots::client_core& c = sim.client(i);
        INFO("client " << i);
        CHECK(c.manifest() == manifest);
        const auto board = boards.find(c.last_snapshot_tick());
        REQUIRE(board != boards.end());
        REQUIRE(c.player_values().size() == 6);
        for (const rules::score_line& line : board->second) {
            const auto held = c.player_values().find(line.player);
            REQUIRE(held != c.player_values().end());
            CHECK(held->second[0] == line.team);
            CHECK(held->second[1] == static_cast<int32_t>(line.score));
            CHECK(held->second[2] == static_cast<int32_t>(line.shots));
        }
        CHECK(c.team_values().size() == 2);
    }
    // The end: the rules ended it; every client's Bye has the teams' values and who won.
    const protocol::match_result result = sim.match().result();
    sim.match().shut_down("match over (its rules ended it)");
    sim.run_ticks(300);
    const auto& soccer = dynamic_cast<const rules::soccer_rules&>(sim.match().game_rules());
    CHECK(result.team_values == std::vector<protocol::game_value>{
                                    {rules::team_red, 0, static_cast<int32_t>(soccer.score(rules::team_red))},
                                    {rules::team_blue, 0, static_cast<int32_t>(soccer.score(rules::team_blue))}});
    CHECK(result.winning_team == soccer.winning_team());
    for (size_t i = 0; i < sim.size(); ++i) {
        const bots::client_core& c = sim.client(i);
        INFO("client " << i << ": " << c.outcome().reason);
        CHECK(c.ended());
        CHECK(c.result() == result);
        CHECK(c.outcome().teams.size() == 2);
    }
}
