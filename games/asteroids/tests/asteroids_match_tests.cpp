// A scripted Asteroids match through apply_tick, against a golden scoreboard and state hash,
// and the same match recorded and replayed to the same scoreboard and hash.
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdio>

#include "games/asteroids/asteroids_rules.hpp"
#include "games/registry.hpp"
#include "server/config/config_json.hpp"
#include "server/config/scoreboard_json.hpp"
#include "server/match/tick_record.hpp"
#include "server/replay/recorder.hpp"
#include "server/world/presets.hpp"
#include "server/world/trig.hpp"
#include "tests/common/record_and_replay.hpp"

using namespace arena;
using world::real;
using world::vec2;

namespace {

// The asteroids preset played by the Asteroids rules.
world::world_config asteroids_game() {
    world::world_config c = world::asteroids_preset();
    c.rules = "asteroids";
    return c;
}

}  // namespace

namespace {

// Four players at tick 0; each turns, thrusts and fires on its own fixed pattern.
struct scripted_result {
    uint64_t hash = 0;
    std::vector<rules::score_line> board;
};

scripted_result scripted_match(uint32_t ticks, replay::recorder* rec = nullptr) {
    world::world w(asteroids_game(), 2026);
    const std::unique_ptr<rules::rules> r = games::make_rules(w);
    REQUIRE(r->has_state());
    std::vector<uint32_t> ships;
    for (uint32_t t = 0; t < ticks; ++t) {
        match::tick_record record;
        record.tick = w.tick();
        if (t == 0) record.joins = {world::player_id{1}, world::player_id{2}, world::player_id{3}, world::player_id{4}};
        for (uint32_t p = 1; p <= 4; ++p) {
            const uint32_t body = r->body_of(p);
            if (body == 0) continue;
            world::player_input in;
            in.thrust = (t / (40 + 10 * p)) % 2 == 0 ? 0.6f : 0.0f;
            in.turn = (t / (25 + 5 * p)) % 3 == 0 ? 0.5f : ((t / (25 + 5 * p)) % 3 == 1 ? -0.4f : 0.0f);
            in.buttons = (t + p) % 4 == 0 ? rules::button_fire : 0;
            record.inputs.push_back({world::body_id{body}, in});
        }
        match::apply_tick(w, *r, record);
        if (rec) REQUIRE(rec->record_tick(record, rules::state_hash(w, *r)).ok());
    }
    if (rec) REQUIRE(rec->finish(w.tick(), rules::state_hash(w, *r)).ok());
    return {rules::state_hash(w, *r), r->scoreboard()};
}

}  // namespace

TEST_CASE("a scripted asteroids match ends at a golden scoreboard and hash", "[rules][asteroids][golden]") {
    const scripted_result a = scripted_match(1800);
    const scripted_result b = scripted_match(1800);
    CHECK(a.hash == b.hash);
    // Written when the rules were made (g++ -O3); a change to the physics or the rules that
    // alters them on purpose updates them in the same commit.
    CHECK(a.hash == 0xc0edf7020bda3144ULL);
    struct expected {
        uint32_t score, kills, deaths, shots, hits, lives;
    };
    const expected golden[] = {
        {200, 1, 0, 101, 1, 3}, {1230, 0, 0, 110, 19, 3}, {490, 0, 0, 104, 8, 3}, {420, 0, 2, 91, 6, 1}};
    REQUIRE(a.board.size() == 4);
    for (size_t k = 0; k < 4; ++k) {
        INFO("player " << a.board[k].player);
        CHECK(a.board[k].player == k + 1);
        CHECK(a.board[k].score == golden[k].score);
        CHECK(a.board[k].kills == golden[k].kills);
        CHECK(a.board[k].deaths == golden[k].deaths);
        CHECK(a.board[k].shots == golden[k].shots);
        CHECK(a.board[k].hits == golden[k].hits);
        CHECK(a.board[k].lives == golden[k].lives);
    }
}

TEST_CASE("a recorded asteroids match replays to the same scoreboard and state hash", "[rules][asteroids][replay]") {
    scripted_result live;
    const testing::replayed_match replayed = testing::record_and_replay(
        asteroids_game(), 2026, "asteroids", [&](replay::recorder& rec) { live = scripted_match(600, &rec); });
    const replay::replay_report& report = replayed.report;
    CHECK(report.complete);
    CHECK_FALSE(report.mismatch);
    CHECK(report.final_hash == live.hash);
    CHECK(config::scoreboard_json(replayed.scoreboard) == config::scoreboard_json(live.board));
    uint32_t shots = 0;
    for (const rules::score_line& s : replayed.scoreboard) shots += s.shots;
    CHECK(shots > 0);
}
