// Soccer's rules, each in closed form: the kick's Δv = J/m, the ball's rolling friction, goals
// and own goals, the kick-off, teams and the clock.
#include <catch2/catch.hpp>

#include "games/registry.hpp"
#include "games/soccer/soccer_params.hpp"
#include "games/soccer/soccer_pitch.hpp"
#include "games/soccer/soccer_rules.hpp"
#include "server/match/tick_record.hpp"

using namespace arena;
using world::real;
using world::vec2;

namespace {

// A pitch and its rules, with `players` joined at tick 0 (ids 1, 2, ...: red, blue, red, ...).
struct pitch_match {
    world::world w;
    std::unique_ptr<rules::rules> game;

    explicit pitch_match(uint32_t players, world::world_config config = rules::soccer_pitch()) : w(config, 7) {
        game = games::make_rules(w);
        match::tick_record first;
        for (uint32_t p = 1; p <= players; ++p) first.joins.push_back(world::player_id{p});
        match::apply_tick(w, *game, first);
    }
    rules::soccer_rules& soccer() { return dynamic_cast<rules::soccer_rules&>(*game); }
    world::body& ball() { return *w.find(soccer().ball()); }
    world::body& body_of(uint32_t player) {
        for (world::body& b : w.bodies())
            if (b.owner == player) return b;
        FAIL("no body for player " << player);
        throw;
    }
    // One tick; `kickers` press the kick button.
    void step(std::initializer_list<uint32_t> kickers = {}) {
        match::tick_record record;
        record.tick = w.tick();
        for (const uint32_t p : kickers) {
            world::player_input in;
            in.buttons = rules::soccer_button_kick;
            record.inputs.push_back({world::body_id{body_of(p).id}, in});
        }
        match::apply_tick(w, *game, record);
    }
};

world::world_config pitch_without_drag() {
    world::world_config c = rules::soccer_pitch();
    c.bodies[1].material.drag_area = 0;
    return c;
}

}  // namespace

TEST_CASE("soccer is a game with its own pitch: walls, goals and a ball on the centre spot", "[soccer]") {
    REQUIRE(games::find("soccer") != nullptr);
    const auto scene = games::scene_by_name("soccer");
    REQUIRE(scene.has_value());
    CHECK(scene->rules == "soccer");
    pitch_match m(0);
    CHECK(m.ball().position == rules::pitch.centre());
    CHECK(m.ball().mass == Approx(0.45f));
    CHECK(m.game->has_state());
    CHECK(m.game->kind_of(m.soccer().ball()) == rules::kind_ball);
}

TEST_CASE("players join the smaller team and start in their own half, facing the other goal", "[soccer][teams]") {
    pitch_match m(5);
    const std::vector<rules::score_line> board = m.game->scoreboard();
    REQUIRE(board.size() == 5);
    for (const rules::score_line& line : board) {
        INFO("player " << line.player);
        CHECK(line.team == (line.player % 2 == 1 ? rules::team_red : rules::team_blue));
        const world::body& b = m.body_of(line.player);
        if (line.team == rules::team_red) {
            CHECK(b.position.x() < rules::pitch.centre().x());
            CHECK(b.angle == 0.0f);
        } else {
            CHECK(b.position.x() > rules::pitch.centre().x());
            CHECK(b.angle == world::pi);
        }
        CHECK(m.game->kind_of(b.id) == rules::kind_player);
    }
    const std::vector<rules::team_line> teams = m.game->teams();
    REQUIRE(teams.size() == 2);
    CHECK(teams[0] == rules::team_line{rules::team_red, "red", 0});
    CHECK(teams[1] == rules::team_line{rules::team_blue, "blue", 0});
}

TEST_CASE("a kick gives the ball Δv = J/m along the line of centres, within reach only", "[soccer][kick]") {
    pitch_match m(1, pitch_without_drag());
    world::body& kicker = m.body_of(1);
    kicker.position = m.ball().position - vec2{1.6f, 0};  // edges 0.1 m apart: within 0.3 m
    const real dv = rules::soccer_params{}.kick_impulse / m.ball().mass;
    m.game->before_step(m.w,
                        {{world::body_id{kicker.id}, {.thrust = 0, .turn = 0, .buttons = rules::soccer_button_kick}}});
    CHECK(m.ball().velocity.x() == Approx(dv));
    CHECK(m.ball().velocity.y() == 0.0f);

    // Out of reach: 1 m between the edges.
    pitch_match far(1, pitch_without_drag());
    world::body& distant = far.body_of(1);
    distant.position = far.ball().position - vec2{2.5f, 0};
    far.step({1});
    CHECK(far.ball().velocity.norm() == 0.0f);
}

TEST_CASE("the ball rolls to a stop under μ·m·g and never rolls back", "[soccer][friction]") {
    pitch_match m(0, pitch_without_drag());
    const rules::soccer_params p;
    m.ball().velocity = {0, 3};  // along the centre line, towards the top wall 9.5 m away
    const real dt = m.w.config().dt;
    const real loss = p.ball_friction * p.gravity * dt;  // m/s a step
    const auto steps = static_cast<int>(3 / loss);
    for (int k = 1; k <= 30; ++k) {
        m.step();
        CHECK(m.ball().velocity.y() == Approx(3 - k * loss).margin(1e-5));
    }
    for (int k = 30; k <= steps + 5; ++k) m.step();
    CHECK(m.ball().velocity.y() == 0.0f);
    // Semi-implicit Euler over a constant deceleration a: the distance is v0²/(2a), less half a
    // step's travel at v0.
    const real a = p.ball_friction * p.gravity;
    CHECK(m.ball().position.y() - rules::pitch.centre().y() == Approx(9 / (2 * a)).epsilon(0.01));
}

TEST_CASE("a ball wholly past a goal line scores for the attackers and for the last toucher", "[soccer][goal]") {
    pitch_match m(2);
    world::body& red = m.body_of(1);
    red.position = m.ball().position - vec2{1.6f, 0};
    m.body_of(2).position = {34, 20};  // blue stands aside (it starts on the ball's way)
    m.ball().velocity = {0, 0};
    m.step({1});  // red kicks towards the right goal (blue's)
    CHECK(m.ball().velocity.x() > 10);
    uint32_t ticks = 0;
    while (m.soccer().score(rules::team_red) == 0 && ticks++ < 600) m.step();
    CHECK(m.soccer().score(rules::team_red) == 1);
    CHECK(m.soccer().score(rules::team_blue) == 0);
    CHECK(m.ball().position.x() > rules::pitch.right + m.ball().radius);
    CHECK(m.game->scoreboard()[0].score == 1);  // player 1's goal
    CHECK(m.game->winning_team() == rules::team_red);
    CHECK(m.soccer().awaiting_kickoff());

    // No second goal while the ball waits in the net; then the kick-off.
    for (uint32_t k = 0; k < rules::soccer_params{}.kickoff_ticks + 1; ++k) m.step();
    CHECK(m.soccer().score(rules::team_red) == 1);
    CHECK_FALSE(m.soccer().awaiting_kickoff());
    CHECK(m.ball().position.x() == Approx(rules::pitch.centre().x()).margin(1e-4));
    CHECK(m.body_of(1).position.x() < rules::pitch.centre().x());
    CHECK(m.body_of(2).position.x() > rules::pitch.centre().x());
}

TEST_CASE("an own goal scores for the other team only", "[soccer][goal]") {
    pitch_match m(2);
    world::body& red = m.body_of(1);
    red.position = m.ball().position + vec2{1.6f, 0};  // red kicks towards its own goal
    m.step({1});
    uint32_t ticks = 0;
    while (m.soccer().score(rules::team_blue) == 0 && ticks++ < 600) m.step();
    CHECK(m.soccer().score(rules::team_blue) == 1);
    CHECK(m.game->scoreboard()[0].score == 0);
    CHECK(m.game->scoreboard()[1].score == 0);
    CHECK(m.game->winning_team() == rules::team_blue);
}

TEST_CASE("the clock ends the match, and equal scores are a draw", "[soccer][clock]") {
    world::world_config c = rules::soccer_pitch();
    c.rules_params = R"({"match_seconds":1})";
    pitch_match m(2, c);
    const uint32_t end = m.soccer().final_tick();
    CHECK(end == 60);
    while (m.w.tick() < end - 1) m.step();
    CHECK_FALSE(m.game->finished());
    m.step();
    CHECK(m.game->finished());
    CHECK(m.game->winning_team() == 0);
    CHECK(m.game->winner() == 0);
}

TEST_CASE("the clock runs in periods, each after the first starting with a kick-off", "[soccer][clock]") {
    world::world_config c = rules::soccer_pitch();
    c.rules_params = R"({"match_seconds":3,"periods":3,"kickoff_ticks":10})";
    pitch_match m(2, c);
    CHECK(m.soccer().period() == 1);
    CHECK(m.soccer().period_end_tick() == 60);
    m.ball().velocity = {0, 3};  // in play, away from the goals
    auto event_names = [&] {
        std::vector<std::string> names;
        const protocol::game_manifest manifest = m.game->manifest();
        for (const rules::declared_event& e : m.game->declared_events()) names.push_back(manifest.events[e.kind].name);
        return names;
    };
    while (m.w.tick() < 59) m.step();
    CHECK(event_names().empty());
    m.step();  // the first period's last tick
    CHECK(event_names() == std::vector<std::string>{"period_end"});
    CHECK(m.game->declared_events()[0].values[0] == 1);
    CHECK(m.soccer().period() == 2);
    CHECK(m.soccer().awaiting_kickoff());
    while (m.soccer().awaiting_kickoff()) m.step();
    CHECK(event_names() == std::vector<std::string>{"kickoff"});
    CHECK(m.ball().position == rules::pitch.centre());
    CHECK(m.ball().velocity == world::vec2{0, 0});
    while (m.w.tick() < 120) m.step();
    CHECK(m.soccer().period() == 3);
    while (!m.game->finished()) m.step();
    CHECK(m.w.tick() == 180);
    CHECK(event_names() == std::vector<std::string>{"full_time"});
    CHECK(m.soccer().period() == 3);  // the last period ends with the clock, not with a kick-off
}

TEST_CASE("soccer's parameters are checked field by field", "[soccer][params]") {
    CHECK(games::config_problem(rules::soccer_pitch()).empty());
    auto problem = [](const char* params) {
        world::world_config c = rules::soccer_pitch();
        c.rules_params = params;
        return games::config_problem(c);
    };
    CHECK(problem(R"({"kick_impulse":0})") == "rules_params.kick_impulse must be a number in (0, 1000]");
    CHECK(problem(R"({"match_seconds":-5})") == "rules_params.match_seconds must be a whole number in [1, 86400]");
    CHECK(problem(R"({"offside":true})") == "unknown field rules_params.offside");
    CHECK(problem(R"({"periods":0})") == "rules_params.periods must be a whole number in [1, 16]");
    CHECK(problem(R"({"ball_friction":0.2,"kickoff_ticks":30})").empty());
    const auto p = rules::parse_soccer_params(R"({"ball_friction":0.2})");
    REQUIRE(p.ok());
    CHECK(p.value.ball_friction == 0.2f);
    CHECK(p.value.kick_impulse == rules::soccer_params{}.kick_impulse);
}
