// Soccer's own bot (soccer_bot.hpp) through arena-bots' client core, over a simulated network:
// three a side with --behavior game kick the ball about and score.
#include <catch2/catch.hpp>

#include "games/soccer/soccer_pitch.hpp"
#include "games/soccer/soccer_rules.hpp"
#include "simnet/match_sim.hpp"

using namespace arena;
using namespace arena::simnet;

TEST_CASE("soccer's bots kick the ball about and score", "[soccer][bots]") {
    sim_options o;
    o.kind = link_kind::datagram;
    o.clients = 6;
    o.delta_snapshots = true;
    o.behavior = bots::behavior_choice::game;
    o.seed = 3;
    o.up.latency = o.down.latency = 30 * ms;
    match::match_config config;
    config.preset = "soccer";
    config.admission.max_players = 6;
    match_sim sim(config, rules::soccer_pitch(), o);
    sim.run_ticks(60 * 90);  // a minute and a half

    const auto& soccer = dynamic_cast<const rules::soccer_rules&>(sim.match().game_rules());
    const uint32_t goals = soccer.score(rules::team_red) + soccer.score(rules::team_blue);
    uint32_t kickers = 0, kicks = 0;
    for (const rules::score_line& line : soccer.scoreboard()) {
        kicks += line.shots;
        kickers += line.shots > 0 ? 1 : 0;
    }
    INFO("goals " << goals << ", kicks " << kicks << " by " << kickers << " players");
    CHECK(goals > 0);
    CHECK(kickers >= 4);  // not one chaser alone: the nearest to the ball changes, passes arrive
}
