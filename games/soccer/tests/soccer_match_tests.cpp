// A scripted soccer match, three a side, through apply_tick: against a golden score and state
// hash, and recorded and replayed to the same hash and scoreboard.
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdio>
#include <map>

#include "games/registry.hpp"
#include "games/soccer/soccer_bot.hpp"
#include "games/soccer/soccer_pitch.hpp"
#include "games/soccer/soccer_rules.hpp"
#include "server/config/scoreboard_json.hpp"
#include "server/match/tick_record.hpp"
#include "server/replay/recorder.hpp"
#include "server/world/trig.hpp"
#include "tests/common/record_and_replay.hpp"

using namespace arena;
using world::real;
using world::vec2;

namespace {

// Turn towards `target` and run when facing it roughly (the bot's steering); kick whenever the
// ball is in reach.
world::player_input run_to(const world::body& own, const world::body& ball, const vec2& target) {
    world::player_input in = rules::run_to(own, target);
    if ((ball.position - own.position).norm() < own.radius + ball.radius + 0.3f) in.buttons = rules::soccer_button_kick;
    return in;
}

// A team's player nearest the ball runs to the spot behind it (seen from the goal it attacks);
// the others wait between the ball and their own goal: goals, saves and own goals happen on
// their own.
world::player_input player_input(const world::body& own, const world::body& ball, uint8_t team, bool nearest) {
    const real attack = team == rules::team_red ? rules::pitch.right : rules::pitch.left;
    const real defend = team == rules::team_red ? rules::pitch.left : rules::pitch.right;
    if (nearest) {
        const vec2 to_goal = (vec2{attack, rules::pitch.centre().y()} - ball.position).normalized();
        // Behind the ball, but on the pitch: a ball on a wall is kicked off it, along the wall.
        const vec2 spot = ball.position - to_goal * (own.radius + ball.radius);
        const real margin = own.radius + 0.1f;
        return run_to(own, ball,
                      {std::clamp(spot.x(), rules::pitch.left + margin, rules::pitch.right - margin),
                       std::clamp(spot.y(), rules::pitch.bottom + margin, rules::pitch.top - margin)});
    }
    const vec2 home{(ball.position.x() + defend) / 2, (ball.position.y() + rules::pitch.centre().y()) / 2};
    return run_to(own, ball, home);
}

struct scripted_result {
    uint64_t hash = 0;
    std::vector<rules::score_line> board;
    uint32_t red = 0, blue = 0;
};

scripted_result scripted_match(uint32_t ticks, replay::recorder* rec = nullptr) {
    world::world w(rules::soccer_pitch(), 2026);
    const std::unique_ptr<rules::rules> r = games::make_rules(w);
    auto& soccer = dynamic_cast<rules::soccer_rules&>(*r);
    for (uint32_t t = 0; t < ticks; ++t) {
        match::tick_record record;
        record.tick = w.tick();
        if (t == 0)
            for (uint32_t p = 1; p <= 6; ++p) record.joins.push_back(world::player_id{p});
        const world::body* ball = w.find(soccer.ball());
        // Each team's player nearest the ball (the lower id on a tie).
        std::map<uint8_t, std::pair<real, uint32_t>> nearest;
        for (const world::body& b : w.bodies()) {
            if (b.owner == 0 || ball == nullptr) continue;
            const uint8_t team = b.owner % 2 == 1 ? rules::team_red : rules::team_blue;
            const real d = (b.position - ball->position).squaredNorm();
            if (!nearest.count(team) || d < nearest[team].first) nearest[team] = {d, b.owner};
        }
        for (const world::body& b : w.bodies()) {
            if (b.owner == 0 || ball == nullptr) continue;
            const uint8_t team = b.owner % 2 == 1 ? rules::team_red : rules::team_blue;
            record.inputs.push_back(
                {world::body_id{b.id}, player_input(b, *ball, team, nearest[team].second == b.owner)});
        }
        match::apply_tick(w, *r, record);
        if (rec) REQUIRE(rec->record_tick(record, rules::state_hash(w, *r)).ok());
    }
    if (rec) REQUIRE(rec->finish(w.tick(), rules::state_hash(w, *r)).ok());
    return {rules::state_hash(w, *r), r->scoreboard(), soccer.score(rules::team_red), soccer.score(rules::team_blue)};
}

}  // namespace

TEST_CASE("a scripted soccer match ends at a golden score and hash", "[soccer][golden]") {
    const scripted_result a = scripted_match(3600);
    const scripted_result b = scripted_match(3600);
    CHECK(a.hash == b.hash);
    INFO("red " << a.red << " blue " << a.blue << " hash " << std::hex << a.hash);
    // Written when the rules were made (g++ -O3); a change to the physics or the rules that
    // alters them on purpose updates them in the same commit.
    CHECK(a.red == 3);
    CHECK(a.blue == 0);
    CHECK(a.hash == 0xec4afcb285668c58ULL);  // periods (two halves) since 2026-12-06
    REQUIRE(a.board.size() == 6);
    uint32_t kicks = 0;
    for (const rules::score_line& line : a.board) kicks += line.shots;
    CHECK(kicks > 0);
}

TEST_CASE("a recorded soccer match replays to the same scoreboard and state hash", "[soccer][replay]") {
    scripted_result live;
    const testing::replayed_match replayed = testing::record_and_replay(
        rules::soccer_pitch(), 2026, "soccer", [&](replay::recorder& rec) { live = scripted_match(1200, &rec); });
    const replay::replay_report& report = replayed.report;
    CHECK(report.complete);
    CHECK_FALSE(report.mismatch);
    CHECK(report.final_hash == live.hash);
    CHECK(config::scoreboard_json(replayed.scoreboard) == config::scoreboard_json(live.board));
    CHECK(replayed.scoreboard.size() == 6);
}
