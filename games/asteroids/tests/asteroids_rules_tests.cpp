// Asteroids rules (games/asteroids/asteroids_rules.hpp): each rule in closed form; the scripted
// match against a golden scoreboard and hash is in asteroids_match_tests.cpp.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "games/asteroids/asteroids_rules.hpp"
#include "games/registry.hpp"
#include "server/config/config_json.hpp"
#include "server/config/scoreboard_json.hpp"
#include "server/match/tick_record.hpp"
#include "server/world/presets.hpp"
#include "server/world/trig.hpp"

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

// The asteroids preset with one still rock of radius 5 in the middle of the field, or none.
world::world_config one_rock(uint32_t rocks = 1) {
    world::world_config c = world::asteroids_preset();
    c.rocks.count = rocks;
    c.rocks.min_radius = 5;
    c.rocks.max_radius = 5;
    c.rocks.max_speed = 0;
    return c;
}

struct game {
    world::world w;
    rules::asteroids_rules r;
    explicit game(const world::world_config& c) : w(c, 7), r(w) {}

    uint32_t join(uint32_t player) {
        const world::player_id owners[] = {world::player_id{player}};
        const uint32_t bodies[] = {w.spawn_players(owners)[0].value()};
        r.on_joins(w, std::vector<uint32_t>{player}, bodies);
        return bodies[0];
    }
    void step(const world::tick_inputs& inputs = {}) {
        r.before_step(w, inputs);
        w.step(inputs);
        r.after_step(w);
    }
    const rules::score_line score(uint32_t player) const {
        for (const rules::score_line& s : r.scoreboard())
            if (s.player == player) return s;
        return {};
    }
    uint32_t rock_count() const {
        uint32_t n = 0;
        for (const world::body& b : w.bodies()) n += r.rock_size(b.id) != 0 ? 1 : 0;
        return n;
    }
    // Puts `player`'s ship `distance` m from the edge of rock `rock`, still, facing it, and
    // fires once: the rock is hit within a few ticks. The rock is stopped first.
    void shoot(uint32_t player, uint32_t rock, real distance = 6) {
        world::body* target = w.find(rock);
        REQUIRE(target);
        target->velocity = {0, 0};
        target->angular_velocity = 0;
        world::body* ship = w.find(r.body_of(player));
        REQUIRE(ship);
        ship->position = target->position - vec2{target->radius + ship->radius + distance, 0};
        ship->velocity = {0, 0};
        ship->angular_velocity = 0;
        ship->angle = 0;
        const uint32_t ship_id = ship->id;
        // Past the cooldown.
        for (uint32_t k = 0; k < r.params().fire_cooldown_ticks; ++k) step();
        ship = w.find(ship_id);
        ship->position = target->position - vec2{target->radius + ship->radius + distance, 0};
        ship->velocity = {0, 0};
        ship->angle = 0;
        world::tick_inputs fire{{world::body_id{ship_id}, {0, 0, rules::button_fire}}};
        step(fire);
        for (int k = 0; k < 30 && r.rock_size(rock) != 0; ++k) step();
        REQUIRE(r.rock_size(rock) == 0);
    }
};

}  // namespace

TEST_CASE("a bullet leaves at J/m_bullet and the ship recoils at exactly -J/m_ship", "[rules][asteroids]") {
    game g(one_rock(0));
    const uint32_t ship = g.join(1);
    g.w.find(ship)->angle = 0.5f;
    const world::cos_sin r = world::compute_cos_sin(0.5f);
    const vec2 facing{r.c, r.s};
    const rules::asteroids_params& p = g.r.params();
    g.r.before_step(g.w, {{world::body_id{ship}, {0, 0, rules::button_fire}}});
    REQUIRE(g.w.bodies().size() == 2);
    const world::body& bullet = g.w.bodies()[1];
    CHECK(g.r.bullet_owner(bullet.id) == 1);
    const vec2 j = facing * p.bullet_impulse;
    // From rest: the whole velocity is the impulse over the mass, both ways.
    CHECK(bullet.velocity == vec2(j * (1.0f / p.bullet_mass)));
    CHECK(bullet.velocity.norm() == Approx(p.bullet_impulse / p.bullet_mass));
    const world::body& s = *g.w.find(ship);
    CHECK(s.velocity == vec2(-j * s.inv_mass));
    CHECK(s.velocity.norm() == Approx(p.bullet_impulse / g.w.config().player.mass));
    // Its own bullet shares the ship's negative group: it passes through its shooter.
    CHECK_FALSE(world::should_collide(s.filter, bullet.filter));
    CHECK(g.score(1).shots == 1);
}

TEST_CASE("make_shot gives the bullet and recoil the rules fire, and shot_of keeps the spawn", "[rules][asteroids]") {
    game g(one_rock(0));
    const uint32_t ship = g.join(1);
    world::body* s = g.w.find(ship);
    s->angle = 2.1f;
    s->velocity = {3.5f, -1.25f};
    const world::body before = *s;  // what a predicting client holds
    const rules::shot predicted = rules::make_shot(before, 1, g.r.params());
    g.r.before_step(g.w, {{world::body_id{ship}, {0, 0, rules::button_fire}}});
    REQUIRE(g.w.bodies().size() == 2);
    const world::body& bullet = g.w.bodies()[1];
    // Bit for bit: the same code from the same state.
    CHECK(bullet.position == predicted.bullet.position);
    CHECK(bullet.velocity == predicted.bullet.velocity);
    world::body recoiled = before;
    recoiled.apply_impulse(predicted.recoil);
    CHECK(g.w.find(ship)->velocity == recoiled.velocity);
    const rules::shot_record* record = g.r.shot_of(bullet.id);
    REQUIRE(record != nullptr);
    CHECK(record->shooter == 1);
    CHECK(record->position == bullet.position);
    CHECK(record->velocity == bullet.velocity);
    CHECK(g.r.shot_of(ship) == nullptr);
    // may_fire: the cooldown's tick itself may fire; the cap counts live bullets.
    const rules::asteroids_params& p = g.r.params();
    CHECK(rules::may_fire(10, 10, 0, p));
    CHECK_FALSE(rules::may_fire(9, 10, 0, p));
    CHECK_FALSE(rules::may_fire(10, 10, p.max_bullets_per_ship, p));
}

TEST_CASE("fire keeps a cooldown, a lifetime and a cap on live bullets", "[rules][asteroids]") {
    game g(one_rock(0));
    const uint32_t ship = g.join(1);
    const rules::asteroids_params& p = g.r.params();
    const world::tick_inputs fire{{world::body_id{ship}, {0, 0, rules::button_fire}}};
    uint32_t first_fire_tick = 0;
    std::vector<uint32_t> fired_at;
    for (uint32_t k = 0; k < 60; ++k) {
        const uint32_t before = g.score(1).shots;
        const uint32_t tick = g.w.tick();
        // Keep the ship still and in the middle, so it meets nothing.
        g.w.find(ship)->velocity = {0, 0};
        g.w.find(ship)->position = {200, 200};
        g.step(fire);
        if (g.score(1).shots != before) fired_at.push_back(tick);
    }
    first_fire_tick = fired_at.front();
    // Every cooldown until the cap, then nothing while the four are alive (72 ticks > 60).
    REQUIRE(fired_at.size() == p.max_bullets_per_ship);
    for (size_t k = 0; k < fired_at.size(); ++k) CHECK(fired_at[k] == first_fire_tick + k * p.fire_cooldown_ticks);
    // The first bullet goes exactly bullet_lifetime_ticks after it was fired.
    const uint32_t first_bullet = ship + 1;
    while (g.w.tick() < first_fire_tick + p.bullet_lifetime_ticks - 1) {
        g.step();
        REQUIRE(g.w.find(first_bullet));
    }
    g.step();
    CHECK_FALSE(g.w.find(first_bullet));
}

TEST_CASE("a split conserves mass and momentum, small rocks go, scores by size", "[rules][asteroids]") {
    game g(one_rock(1));
    g.join(1);
    for (int k = 0; k < 121; ++k) g.step();  // past the join's invulnerability
    const uint32_t rock = 1;
    REQUIRE(g.r.rock_size(rock) == 3);
    // Watch the step in which the bullet hits: the rock as it left the step, then the pieces.
    world::body* target = g.w.find(rock);
    target->velocity = {3, -1};
    const real mass = target->mass;
    g.shoot(1, rock);
    std::vector<const world::body*> pieces;
    for (const world::body& b : g.w.bodies())
        if (g.r.rock_size(b.id) == 2) pieces.push_back(&b);
    REQUIRE(pieces.size() == 2);
    CHECK(pieces[0]->mass + pieces[1]->mass == mass);
    CHECK(g.score(1).score == 20);
    CHECK(g.score(1).hits == 1);
    // Symmetric about the rock's velocity: their mean is it, their difference is across it.
    const vec2 mean = (pieces[0]->velocity + pieces[1]->velocity) * 0.5f;
    const vec2 apart = pieces[0]->velocity - pieces[1]->velocity;
    CHECK(apart.dot(mean) == Approx(0).margin(1e-3));
    CHECK(apart.norm() == Approx(2 * g.r.params().split_impulse / pieces[0]->mass));

    // Medium → two small (50), small → nothing (100).
    const uint32_t medium = pieces[0]->id;
    g.shoot(1, medium);
    CHECK(g.score(1).score == 70);
    uint32_t small = 0;
    for (const world::body& b : g.w.bodies())
        if (g.r.rock_size(b.id) == 1) small = b.id;
    REQUIRE(small != 0);
    const uint32_t rocks_before = g.rock_count();
    const size_t bodies_before = g.w.bodies().size();
    g.shoot(1, small);
    CHECK(g.score(1).score == 170);
    CHECK(g.score(1).hits == 3);
    CHECK(g.rock_count() == rocks_before - 1);
    CHECK(g.w.bodies().size() == bodies_before - 1);  // the rock; its bullet was already gone
}

TEST_CASE("momentum across a split, measured in the step of the hit", "[rules][asteroids]") {
    // The rules' split alone: the rock after the step (the bullet's push included) against
    // the two pieces that replace it.
    game g(one_rock(1));
    g.join(1);
    for (int k = 0; k < 121; ++k) g.step();
    world::body* target = g.w.find(1);
    target->velocity = {2, 5};
    target->angular_velocity = 0;
    world::body* ship = g.w.find(g.r.body_of(1));
    ship->position = target->position - vec2{target->radius + ship->radius + 1, 0};
    ship->velocity = {0, 0};
    ship->angle = 0;
    const uint32_t ship_id = ship->id;
    g.r.before_step(g.w, {{world::body_id{ship_id}, {0, 0, rules::button_fire}}});
    vec2 before{0, 0};
    for (int k = 0; k < 30; ++k) {
        g.w.step({});
        if (const world::body* rock = g.w.find(1)) before = rock->velocity * rock->mass;
        g.r.after_step(g.w);
        if (g.r.rock_size(1) == 0) break;
    }
    REQUIRE(g.r.rock_size(1) == 0);
    vec2 after{0, 0};
    for (const world::body& b : g.w.bodies())
        if (g.r.rock_size(b.id) == 2) after += b.velocity * b.mass;
    CHECK(after.x() == Approx(before.x()).epsilon(1e-5));
    CHECK(after.y() == Approx(before.y()).epsilon(1e-5));
}

TEST_CASE("a ship hit by a rock respawns exactly 120 ticks later, invulnerable for 120, and the fourth death ends play",
          "[rules][asteroids]") {
    game g(one_rock(1));
    g.join(1);
    CHECK(g.r.invulnerable(g.w, 1));
    const auto ram = [&g] {
        while (g.r.invulnerable(g.w, 1)) g.step();
        world::body* rock = g.w.find(1);
        rock->velocity = {0, 0};
        world::body* ship = g.w.find(g.r.body_of(1));
        ship->position = rock->position - vec2{rock->radius + ship->radius + 0.5f, 0};
        ship->velocity = {10, 0};
        for (int k = 0; k < 30 && g.r.body_of(1) != 0; ++k) g.step();
        REQUIRE(g.r.body_of(1) == 0);
        return g.w.tick();
    };
    for (uint32_t death = 1; death <= 3; ++death) {
        const uint32_t died = ram();
        CHECK(g.score(1).deaths == death);
        CHECK(g.score(1).lives == 3 - death);
        while (g.r.body_of(1) == 0) g.step();
        CHECK(g.w.tick() == died + 120);
        CHECK(g.r.invulnerable(g.w, 1));
        // It passes through everything: its mask is empty until 120 ticks on.
        for (int k = 0; k < 119; ++k) g.step();
        CHECK(g.r.invulnerable(g.w, 1));
        g.step();
        CHECK_FALSE(g.r.invulnerable(g.w, 1));
    }
    ram();
    CHECK(g.score(1).deaths == 4);
    CHECK(g.score(1).out);
    for (int k = 0; k < 300; ++k) g.step();
    CHECK(g.r.body_of(1) == 0);
}

TEST_CASE("shooting another player's ship scores 200 and a kill", "[rules][asteroids]") {
    game g(one_rock(0));
    g.join(1);
    g.join(2);
    for (int k = 0; k < 121; ++k) g.step();
    world::body* a = g.w.find(g.r.body_of(1));
    world::body* b = g.w.find(g.r.body_of(2));
    a->position = {100, 100};
    a->velocity = {0, 0};
    a->angle = 0;
    b->position = {110, 100};
    b->velocity = {0, 0};
    const uint32_t shooter = a->id;
    g.step({{world::body_id{shooter}, {0, 0, rules::button_fire}}});
    for (int k = 0; k < 30 && g.r.body_of(2) != 0; ++k) g.step();
    CHECK(g.r.body_of(2) == 0);
    CHECK(g.score(1).score == 200);
    CHECK(g.score(1).kills == 1);
    CHECK(g.score(1).hits == 1);
    CHECK(g.score(2).deaths == 1);
}

TEST_CASE("when every rock is gone a wave of one more large rock spawns away from the ships", "[rules][asteroids]") {
    game g(one_rock(0));
    g.join(1);
    g.step();
    // No rocks at the start: the first wave (of one) spawns at once; the wave counts up.
    CHECK(g.r.wave() == 1);
    CHECK(g.rock_count() == 1);
    const world::body* ship = g.w.find(g.r.body_of(1));
    for (const world::body& b : g.w.bodies()) {
        if (g.r.rock_size(b.id) == 0) continue;
        CHECK(g.r.rock_size(b.id) == 3);
        CHECK(world::displacement(b.position, ship->position, g.w.config()).norm() >
              b.radius + ship->radius + g.r.params().spawn_clearance);
    }
}

TEST_CASE("sandbox rules keep no state: the state hash is the world's", "[rules]") {
    world::world w(world::platformer_preset(), 3);
    const std::unique_ptr<rules::rules> r = games::make_rules(w);
    CHECK_FALSE(r->has_state());
    match::tick_record t;
    t.joins = {world::player_id{1}};
    match::apply_tick(w, *r, t);
    CHECK(rules::state_hash(w, *r) == w.hash());
    CHECK(r->scoreboard().empty());
    // A config that names the Asteroids rules gets them, and its JSON carries them.
    world::world a(asteroids_game(), 3);
    CHECK(games::make_rules(a)->has_state());
    const auto back = config::parse_config_json(config::config_to_json(asteroids_game()));
    CHECK(back.value.rules == "asteroids");
    CHECK(config::config_to_json(world::platformer_preset()).find("\"rules\"") == std::string::npos);
}

TEST_CASE("the scoreboard JSON lists every player in id order with its name", "[rules]") {
    const rules::score_line lines[] = {{1, 70, 0, 1, 12, 3, 2, false}, {4, 200, 1, 0, 5, 1, 3, false}};
    const std::string names[] = {"ada", "bob \"b\""};
    CHECK(config::scoreboard_json(lines, names) ==
          R"([{"deaths":1,"hits":3,"kills":0,"name":"ada","player":1,"score":70,"shots":12},)"
          R"({"deaths":0,"hits":1,"kills":1,"name":"bob \"b\"","player":4,"score":200,"shots":5}])");
    CHECK(config::scoreboard_json({}) == "[]");
}

TEST_CASE("the rules tell what happened (a rock hit, a ship lost, its respawn, a new wave) and who wins",
          "[rules][asteroids]") {
    game g(one_rock(1));
    g.join(1);
    g.join(2);
    CHECK(g.r.winner() == 0);  // a tie at 0: nobody
    for (int k = 0; k < 121; ++k) g.step();
    g.shoot(1, 1);  // returns right after the step of the hit
    REQUIRE(g.r.events().size() == 1);
    const rules::game_event hit = g.r.events()[0];
    CHECK(hit.kind == rules::event_kind::rock_hit);
    CHECK(hit.player == 1);
    CHECK(hit.body == 1);
    CHECK(hit.size == 3);
    CHECK(hit.value == g.r.params().score_large);
    CHECK(g.r.winner() == 1);
    g.step();
    CHECK(g.r.events().empty());  // each step tells its own

    // Player 2 rams a piece: destroyed by a rock (nobody's bullet), then respawned.
    uint32_t piece = 0;
    for (const world::body& b : g.w.bodies())
        if (g.r.rock_size(b.id) == 2) piece = b.id;
    REQUIRE(piece != 0);
    const uint32_t old_ship = g.r.body_of(2);
    world::body* rock = g.w.find(piece);
    rock->velocity = {0, 0};
    world::body* ship = g.w.find(old_ship);
    ship->position = rock->position - vec2{rock->radius + ship->radius + 0.5f, 0};
    ship->velocity = {10, 0};
    for (int k = 0; k < 30 && g.r.body_of(2) != 0; ++k) g.step();
    REQUIRE(g.r.body_of(2) == 0);
    const auto lost = std::find_if(g.r.events().begin(), g.r.events().end(), [](const rules::game_event& e) {
        return e.kind == rules::event_kind::ship_destroyed;
    });
    REQUIRE(lost != g.r.events().end());
    CHECK(lost->player == 2);
    CHECK(lost->other == 0);
    CHECK(lost->body == old_ship);
    CHECK(g.score(2).state == rules::player_state::respawning);
    while (g.r.body_of(2) == 0) g.step();
    REQUIRE(g.r.events().size() == 1);
    CHECK(g.r.events()[0].kind == rules::event_kind::respawn);
    CHECK(g.r.events()[0].player == 2);
    CHECK(g.r.events()[0].body == g.r.body_of(2));
    CHECK(g.score(2).state == rules::player_state::playing);

    // A field without rocks: the first step brings a wave of one more than the last (none).
    game empty(one_rock(0));
    empty.step();
    REQUIRE(empty.r.events().size() == 1);
    CHECK(empty.r.events()[0].kind == rules::event_kind::wave);
    CHECK(empty.r.events()[0].value == 1);
}

namespace {

// Puts body `id` at `at`, still and facing +x.
void hold(world::world& w, uint32_t id, vec2 at) {
    world::body* b = w.find(id);
    REQUIRE(b);
    b->position = at;
    b->velocity = {0, 0};
    b->angular_velocity = 0;
    b->angle = 0;
}

// Lag compensation: ship 1 fires along +x at ship 2, which stood 10 m ahead in the line of fire
// until the moment of the shot, then left it (30 m up). The bullet needs about 15 ticks to get
// there. Returns whether ship 2 was destroyed, for a shot whose input rewinds `rewind`; a hit
// tells the victim how far back it was judged (shot_rewound, just before its ship_destroyed).
bool shot_at_leaving_target_hits(uint16_t rewind) {
    game g(one_rock(1));
    const uint32_t shooter = g.join(1);
    const uint32_t victim = g.join(2);
    uint32_t rock = 0;
    for (const world::body& b : g.w.bodies())
        if (g.r.rock_size(b.id) != 0) rock = b.id;
    const vec2 gun{20, 50}, ahead{30, 50}, away{30, 80};
    const auto tick = [&](vec2 victim_at, const world::tick_inputs& inputs = {}) {
        hold(g.w, shooter, gun);
        if (g.r.body_of(2) == victim) hold(g.w, victim, victim_at);
        if (rock != 0 && g.w.find(rock)) hold(g.w, rock, {80, 10});
        g.step(inputs);
    };
    // Past both ships' invulnerability after joining, and half a second in the line of fire
    // (an invulnerable ship is no target, in the past either).
    for (uint32_t k = 0; k <= g.r.params().invulnerable_ticks + 30; ++k) tick(ahead);
    const real victim_radius = g.w.find(victim)->radius;
    world::player_input fire{0, 0, rules::button_fire};
    fire.rewind = rewind;
    tick(away, {{world::body_id{shooter}, fire}});
    for (uint32_t k = 0; k < 40 && g.score(1).kills == 0; ++k) tick(away);
    if (g.score(1).kills == 0) return false;
    // The shooter hears where the target was judged: where it stood in the past, in mm.
    const auto judged = g.r.declared_events();
    REQUIRE(judged.size() == 1);
    CHECK(judged[0].kind == rules::judged_in_past);
    CHECK(judged[0].values[0] == 1);
    CHECK(judged[0].values[1] == 30000);
    CHECK(judged[0].values[2] == 50000);
    CHECK(judged[0].values[3] == std::lround(victim_radius * 1000.0f));
    const auto& events = g.r.events();
    const auto told = std::find_if(events.begin(), events.end(), [](const rules::game_event& e) {
        return e.kind == rules::event_kind::shot_rewound;
    });
    REQUIRE(told != events.end());
    CHECK(told->player == 2);
    CHECK(told->other == 1);
    CHECK(told->body == victim);
    CHECK(told->value == rewind);
    REQUIRE(told + 1 != events.end());
    CHECK((told + 1)->kind == rules::event_kind::ship_destroyed);
    CHECK((told + 1)->body == victim);
    return true;
}

}  // namespace

TEST_CASE("a rewound shot hits the target where its shooter saw it, and only there", "[rules][asteroids][lag]") {
    // Without a rewind the target has left the line before the bullet gets there: a miss.
    CHECK_FALSE(shot_at_leaving_target_hits(0));
    // Seen 5 ticks late, the target had left as well.
    CHECK_FALSE(shot_at_leaving_target_hits(5 * 256));
    // Seen 20 ticks late (333 ms at 60 Hz), the target was still in the line: a hit.
    CHECK(shot_at_leaving_target_hits(20 * 256));
}

namespace {

// Ticks from a shot, fired from 40 m away at a still rock of radius 5, to the rock's hit, for a
// shot whose input rewinds `rewind`.
uint32_t ticks_to_hit_a_large_rock(uint16_t rewind) {
    game g(one_rock(1));
    const uint32_t shooter = g.join(1);
    uint32_t rock = 0;
    for (const world::body& b : g.w.bodies())
        if (g.r.rock_size(b.id) != 0) rock = b.id;
    REQUIRE(rock != 0);
    const auto tick = [&](const world::tick_inputs& inputs = {}) {
        hold(g.w, shooter, {20, 50});
        if (g.r.rock_size(rock) != 0) hold(g.w, rock, {60, 50});
        g.step(inputs);
    };
    // Past the cooldown, and long enough still for the history to hold the rock there.
    for (uint32_t k = 0; k < 70; ++k) tick();
    world::player_input fire{0, 0, rules::button_fire};
    fire.rewind = rewind;
    tick({{world::body_id{shooter}, fire}});
    for (uint32_t k = 1; k <= 60; ++k) {
        if (g.r.rock_size(rock) == 0) return k;
        tick();
    }
    return 0;
}

}  // namespace

// A rewound shot is judged against the rock's bounding circle where the bullet's sweep first
// reaches it, not where the rock's centre lies: a rock much larger than one tick of the bullet's
// flight is hit no later than the present's contact would hit it.
TEST_CASE("a rewound shot hits a large rock where its sweep first reaches it", "[rules][asteroids][lag]") {
    const uint32_t present = ticks_to_hit_a_large_rock(0);
    REQUIRE(present != 0);
    const uint32_t rewound = ticks_to_hit_a_large_rock(5 * 256);
    REQUIRE(rewound != 0);
    CHECK(rewound <= present);
    // The bounding circle reaches beyond the polygon (its corners lie 0.6 to 1 radius out): at
    // most 2 m, three steps of the bullet.
    CHECK(rewound + 4 >= present);
}

TEST_CASE("a sweep tells where along its step it first comes within reach", "[rules][lag]") {
    const world::world_config c = world::asteroids_preset();
    // A 5 m reach whose centre lies 5.5 steps ahead: reached half way through the step.
    const auto half = rules::sweep_hits(vec2{10, 10}, vec2{1, 0}, vec2{15.5f, 10}, 5, c);
    REQUIRE(half);
    CHECK(*half == Approx(0.5f));
    // Six steps ahead: out of reach for the whole step.
    CHECK_FALSE(rules::sweep_hits(vec2{10, 10}, vec2{1, 0}, vec2{16.5f, 10}, 5, c));
    // Starting within reach: at once. Passing beside it within reach: where the circle begins.
    CHECK(rules::sweep_hits(vec2{10, 10}, vec2{1, 0}, vec2{12, 10}, 5, c) == 0);
    const auto beside = rules::sweep_hits(vec2{10, 10}, vec2{4, 0}, vec2{16, 13}, 5, c);
    REQUIRE(beside);
    CHECK(*beside == Approx(0.5f));  // (12, 10) is 5 m from (16, 13)
    // The short way round a wrapping world: a target just over the edge ahead.
    const auto wrapped = rules::sweep_hits(vec2{c.size.x() - 1, 10}, vec2{1, 0}, vec2{4.5f, 10}, 5, c);
    REQUIRE(wrapped);
    CHECK(*wrapped == Approx(0.5f));
}

TEST_CASE("the hit history keeps a bounded past and interpolates between ticks", "[rules][lag]") {
    world::world_config c = world::asteroids_preset();
    rules::hit_history h;
    for (uint32_t t = 1; t <= 200; ++t)
        h.record(t, {{7, vec2{static_cast<real>(t), 10}, 1}, {9, vec2{static_cast<real>(t), 300}, 1}}, c);
    CHECK(h.ticks() == rules::hit_history::depth);  // 66 ticks, however long it ran
    std::vector<rules::hit_history::target> seen;
    const auto at = [&](uint16_t rewind) {
        seen.clear();
        // Near (190, 10): target 9, over 100 m away, is not even looked at.
        h.rewound_near(200, rewind, vec2{190, 10}, 80, c,
                       [&](const rules::hit_history::target& t) { seen.push_back(t); });
        REQUIRE(seen.size() == 1);
        return seen[0].position.x();
    };
    CHECK(at(0) == 200);
    CHECK(at(10 * 256) == 190);
    CHECK(at(10 * 256 + 128) == Approx(189.5f));
    CHECK(at(world::max_rewind) == 136);  // the most an input rewinds: 64 ticks back
}

// A target of the past may be gone from the present (a rock split since): a sweep that meets
// it hits nothing, and nothing is told.
TEST_CASE("each hit judged in the past is told once, with its shooter and where", "[rules][asteroids][lag]") {
    game g(asteroids_game());
    g.join(1);
    uint32_t judged = 0, rock_hits = 0;
    for (uint32_t t = 0; t < 3000; ++t) {
        world::player_input in{0, 0.3f, rules::button_fire};
        in.rewind = 5 * 256;
        g.step({{world::body_id{g.r.body_of(1)}, in}});
        for (const rules::declared_event& e : g.r.declared_events()) {
            CHECK(e.kind == rules::judged_in_past);
            CHECK(e.values[0] == 1);
            CHECK(e.values[3] > 0);
            ++judged;
        }
        for (const rules::game_event& e : g.r.events())
            rock_hits += e.kind == rules::event_kind::rock_hit && e.player == 1 ? 1 : 0;
    }
    CHECK(rock_hits > 0);
    CHECK(judged == rock_hits);
    CHECK(judged == g.score(1).hits);
}
