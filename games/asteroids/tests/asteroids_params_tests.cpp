// A config's rules_params (games/asteroids/asteroids_params.hpp): what Asteroids reads from it, what
// it refuses and how, and that the match, the config's JSON and a predicting client all play by
// the same numbers.
#include <catch2/catch.hpp>
#include <stdexcept>

#include "client_sim/own_shots.hpp"
#include "games/asteroids/asteroids_rules.hpp"
#include "games/registry.hpp"
#include "server/config/config_json.hpp"
#include "server/config/modes.hpp"
#include "server/config/world_choice.hpp"
#include "server/world/hash.hpp"
#include "server/world/presets.hpp"

using namespace arena;

namespace {

world::world_config asteroids_with(const std::string& params) {
    auto c = config::parse_config_json(R"({"preset": "asteroids", "rules": "asteroids", "rocks": {"count": 0},
                                           "rules_params": )" +
                                       params + "}");
    REQUIRE(c);
    return c.value;
}

}  // namespace

TEST_CASE("no rules_params, or an empty object, is the game's defaults", "[rules][params]") {
    const rules::asteroids_params defaults;
    for (const char* text : {"", "{}"}) {
        const auto p = rules::parse_asteroids_params(text);
        REQUIRE(p);
        CHECK(p.value.lives == defaults.lives);
        CHECK(p.value.bullet_impulse == defaults.bullet_impulse);
        CHECK(p.value.score_ship == defaults.score_ship);
    }
}

TEST_CASE("every field given is read, the rest keep their defaults", "[rules][params]") {
    const auto p = rules::parse_asteroids_params(
        R"({"lives": 5, "bullet_impulse": 4, "fire_cooldown_ticks": 0, "score_ship": 500, "wave_rock_radius": 2.5})");
    REQUIRE(p);
    CHECK(p.value.lives == 5);
    CHECK(p.value.bullet_impulse == 4.0f);
    CHECK(p.value.fire_cooldown_ticks == 0);
    CHECK(p.value.score_ship == 500);
    CHECK(p.value.wave_rock_radius == 2.5f);
    CHECK(p.value.bullet_mass == rules::asteroids_params{}.bullet_mass);
}

TEST_CASE("a field of the wrong type, out of range or unknown is refused by name", "[rules][params]") {
    const auto error = [](const std::string& text) {
        return rules::parse_asteroids_params(text).error;
    };
    CHECK(error(R"({"livez": 3})") == "unknown field rules_params.livez");
    CHECK(error(R"({"lives": "3"})") == "rules_params.lives must be a whole number in [0, 1000]");
    CHECK(error(R"({"lives": -1})") == "rules_params.lives must be a whole number in [0, 1000]");
    CHECK(error(R"({"lives": 2.5})") == "rules_params.lives must be a whole number in [0, 1000]");
    CHECK(error(R"({"bullet_mass": 0})") == "rules_params.bullet_mass must be a number in (0, 1000]");
    CHECK(error(R"({"max_bullets_per_ship": 65})") ==
          "rules_params.max_bullets_per_ship must be a whole number in [0, 64]");
    CHECK(error(R"({"split_impulse": 1e300})") == "rules_params.split_impulse must be a number in [0, 100000]");
    CHECK(error("[1]") == "rules_params must be an object");
}

TEST_CASE("a bullet leaves at the configured J/m_bullet", "[rules][params]") {
    world::world w(asteroids_with(R"({"bullet_impulse": 4, "bullet_mass": 0.1})"), 7);
    const std::unique_ptr<rules::rules> r = games::make_rules(w);
    const world::player_id owners[] = {world::player_id{1}};
    const uint32_t ship = w.spawn_players(owners)[0].value();
    r->on_joins(w, std::vector<uint32_t>{1}, std::vector<uint32_t>{ship});
    r->before_step(w, {{world::body_id{ship}, {0, 0, rules::button_fire}}});
    REQUIRE(w.bodies().size() == 2);
    CHECK(w.bodies()[1].velocity.norm() == Approx(4.0 / 0.1));  // 40 m/s, as the defaults' 2 / 0.05
    CHECK(w.bodies()[1].mass == Approx(0.1));
}

TEST_CASE("the parameters are part of the config: its JSON, canonical, and its hash", "[rules][params]") {
    const world::world_config a = asteroids_with(R"({"score_ship": 300, "lives": 1})");
    CHECK(a.rules_params == R"({"lives":1,"score_ship":300})");  // keys sorted, no spaces
    const auto back = config::parse_config_json(config::config_to_json(a));
    REQUIRE(back);
    CHECK(back.value.rules_params == a.rules_params);
    CHECK(world::config_hash(back.value) == world::config_hash(a));
    CHECK(world::config_hash(a) != world::config_hash(asteroids_with("{}")));
    // A config without them keeps its JSON and hash.
    world::world_config plain = world::asteroids_preset();
    CHECK(config::config_to_json(plain).find("rules_params") == std::string::npos);
}

TEST_CASE("the match refuses parameters its game does not take, wherever they come from", "[rules][params]") {
    world::world_config bad = asteroids_with("{}");
    bad.rules_params = R"({"lives": 9999})";
    world::world w(bad, 1);
    CHECK_THROWS_AS(games::make_rules(w), std::invalid_argument);
    world::world_config sandbox = world::platformer_preset();
    sandbox.rules_params = R"({"lives": 1})";
    CHECK(games::config_problem(sandbox) == "rules_params: the sandbox rules take no parameters");
    // A --modes file names the mode's entry and the field.
    const auto modes = config::parse_modes_json(
        R"({"modes": [{"name": "duel", "preset": "asteroids", "world": {"rules_params": {"lives": "x"}}}]})");
    REQUIRE_FALSE(modes);
    CHECK(modes.error == "modes[0]: world: rules_params.lives must be a whole number in [0, 1000]");
    // A mode of the asteroids preset takes Asteroids' parameters.
    const auto good = config::parse_modes_json(
        R"({"modes": [{"name": "one-life", "preset": "asteroids", "world": {"rules_params": {"lives": 0}}}]})");
    REQUIRE(good);
    CHECK(good.value[0].world.rules_params == R"({"lives":0})");
}

TEST_CASE("a client predicts its own shots with the server's parameters", "[rules][params]") {
    const world::world_config c = asteroids_with(R"({"fire_cooldown_ticks": 30, "bullet_impulse": 3})");
    const bots::own_shots shots(c, 1);
    CHECK(shots.enabled());
    const auto* rule = dynamic_cast<const rules::asteroids_shot_rule*>(shots.rule());
    REQUIRE(rule != nullptr);
    CHECK(rule->params().fire_cooldown_ticks == 30);
    CHECK(rule->params().bullet_impulse == 3.0f);
    CHECK(rule->cooldown_ticks() == 30);
    world::world_config unreadable = c;
    unreadable.rules_params = R"({"lives": -4})";
    CHECK_FALSE(bots::own_shots(unreadable, 1).enabled());  // no numbers to predict by
}
