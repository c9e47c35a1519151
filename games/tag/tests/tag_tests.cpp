// Tag's rules in closed form (who is "it", passing it on, no tag-back, time as "it", the
// winners), and a scripted match recorded and replayed to the same hash and scoreboard: the
// tutorial's steps 4 and 5 (docs/GAMES.md).
#include <catch2/catch.hpp>

#include "games/registry.hpp"
#include "games/tag/tag_rules.hpp"
#include "server/config/scoreboard_json.hpp"
#include "server/match/tick_record.hpp"
#include "server/world/trig.hpp"
#include "tests/common/record_and_replay.hpp"

using namespace arena;
using world::vec2;

namespace {

world::world_config tag_room() {
    return games::scene_by_name("tag").value();
}

// A world of `players` joined at tick 0, and its tag rules.
struct room {
    world::world w{tag_room(), 11};
    std::unique_ptr<rules::rules> game = games::make_rules(w);
    rules::tag_rules& tag = dynamic_cast<rules::tag_rules&>(*game);

    explicit room(uint32_t players) {
        match::tick_record first;
        for (uint32_t p = 1; p <= players; ++p) first.joins.push_back(world::player_id{p});
        match::apply_tick(w, *game, first);
    }
    world::body& body_of(uint32_t player) {
        for (world::body& b : w.bodies())
            if (b.owner == player) return b;
        throw std::logic_error("no body");
    }
    void step(uint32_t ticks = 1) {
        for (uint32_t t = 0; t < ticks; ++t) {
            match::tick_record record;
            record.tick = w.tick();
            match::apply_tick(w, *game, record);
        }
    }
    // Puts `a` and `b` side by side, touching, far from everything else.
    void touch(uint32_t a, uint32_t b) {
        body_of(a).position = {30, 52};
        body_of(b).position = {30 + 2 * body_of(a).radius + 0.01f, 52};
        body_of(a).velocity = {1, 0};
        body_of(b).velocity = {-1, 0};
    }
};

}  // namespace

TEST_CASE("the first player is it, and time as it counts a tick at a time", "[tag]") {
    room r(3);
    CHECK(r.tag.it() == 1);
    r.step(10);
    CHECK(r.tag.ticks_it(1) == 11);  // the join's tick, then ten
    CHECK(r.tag.ticks_it(2) == 0);
    CHECK(r.game->scoreboard()[0].values[0] == 1);  // role: it
    CHECK(r.game->scoreboard()[1].values[0] == 2);  // role: runner
}

TEST_CASE("passing it on retags both bodies, so that clients draw the new it", "[tag]") {
    room r(2);
    std::vector<uint32_t> retagged;
    r.game->take_retagged(retagged);  // the first "it", at the join
    const uint32_t first = r.body_of(1).id, second = r.body_of(2).id;
    CHECK(r.game->kind_of(first) == 2);   // it
    CHECK(r.game->kind_of(second) == 1);  // a runner
    retagged.clear();
    r.step(60);
    r.game->take_retagged(retagged);
    CHECK(retagged.empty());  // nothing changed hands
    r.touch(1, 2);
    r.step();
    r.game->take_retagged(retagged);
    CHECK(retagged == std::vector<uint32_t>{first, second});
    CHECK(r.game->kind_of(first) == 1);
    CHECK(r.game->kind_of(second) == 2);
    retagged.clear();
    r.game->take_retagged(retagged);
    CHECK(retagged.empty());  // taken once
}

TEST_CASE("a touch passes it on, told as an event, with no tag-back for a second", "[tag]") {
    room r(2);
    r.step(60);  // past the first player's second of grace
    r.touch(1, 2);
    r.step();
    CHECK(r.tag.it() == 2);
    REQUIRE(r.game->declared_events().size() == 1);
    CHECK(r.game->declared_events()[0].values[0] == 1);  // who tagged
    CHECK(r.game->declared_events()[0].values[1] == 2);  // whom
    r.touch(2, 1);                                       // straight back: immune
    r.step(5);
    CHECK(r.tag.it() == 2);
    r.step(60);
    r.touch(2, 1);
    r.step();
    CHECK(r.tag.it() == 1);
}

TEST_CASE("the least time as it wins, ties together", "[tag]") {
    room r(3);
    CHECK(r.game->winners() == std::vector<uint32_t>{2, 3});
    r.step(60);
    r.touch(1, 2);
    r.step(3);
    CHECK(r.game->winners() == std::vector<uint32_t>{3});
    CHECK(r.game->manifest().rank_ascending);
}

TEST_CASE("a recorded tag match replays to the same scoreboard and hash", "[tag][replay]") {
    // Four players; each turns towards the nearest other player and runs.
    auto play = [](replay::recorder* rec) {
        world::world w(tag_room(), 2026);
        const auto game = games::make_rules(w);
        uint32_t tags = 0;
        for (uint32_t t = 0; t < 1800; ++t) {
            match::tick_record record;
            record.tick = w.tick();
            if (t == 0)
                for (uint32_t p = 1; p <= 4; ++p) record.joins.push_back(world::player_id{p});
            for (const world::body& b : w.bodies()) {
                if (b.owner == 0) continue;
                const world::body* near = nullptr;
                for (const world::body& o : w.bodies())
                    if (o.owner != 0 && o.id != b.id &&
                        (!near ||
                         (o.position - b.position).squaredNorm() < (near->position - b.position).squaredNorm()))
                        near = &o;
                if (!near) continue;
                const vec2 way = near->position - b.position;
                const world::cos_sin f = world::compute_cos_sin(b.angle);
                const float cross = f.c * way.y() - f.s * way.x();
                record.inputs.push_back({world::body_id{b.id}, {.thrust = 0.8f, .turn = cross > 0 ? 1.0f : -1.0f}});
            }
            match::apply_tick(w, *game, record);
            tags += static_cast<uint32_t>(game->declared_events().size());
            if (rec) REQUIRE(rec->record_tick(record, rules::state_hash(w, *game)).ok());
        }
        if (rec) REQUIRE(rec->finish(w.tick(), rules::state_hash(w, *game)).ok());
        return std::make_tuple(rules::state_hash(w, *game), game->scoreboard(), tags);
    };
    std::tuple<uint64_t, std::vector<rules::score_line>, uint32_t> live;
    const testing::replayed_match replayed =
        testing::record_and_replay(tag_room(), 2026, "tag", [&](replay::recorder& rec) { live = play(&rec); });
    CHECK(std::get<2>(live) > 0);  // it was passed on
    CHECK(replayed.report.complete);
    CHECK_FALSE(replayed.report.mismatch);
    CHECK(replayed.report.final_hash == std::get<0>(live));
    CHECK(config::scoreboard_json(replayed.scoreboard) == config::scoreboard_json(std::get<1>(live)));
}

TEST_CASE("tag takes no parameters: any field is refused by name", "[tag][params]") {
    world::world_config c = tag_room();
    CHECK(games::config_problem(c).empty());
    c.rules_params = "{}";
    CHECK(games::config_problem(c).empty());
    c.rules_params = R"({"tag_back_ticks":30})";
    CHECK(games::config_problem(c) == "unknown field rules_params.tag_back_ticks");
}
