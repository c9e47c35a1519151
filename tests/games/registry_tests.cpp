// The registry of games (games/registry.hpp): every game games/CMakeLists.txt registers, found
// by name, checked through its own parameters, with a built-in mode when it is made for a scene;
// and a name this build does not have, refused where a game is played but read where a world is
// only drawn.
#include <catch2/catch.hpp>
#include <stdexcept>
#include <string>

#include "games/registry.hpp"
#include "server/config/config_json.hpp"
#include "server/config/modes.hpp"
#include "server/world/presets.hpp"

using namespace arena;

TEST_CASE("the registry lists the sandbox first, then every registered game once", "[games]") {
    const auto games = games::all();
    REQUIRE(games.size() >= 2);
    CHECK(games[0]->name == "sandbox");
    CHECK(games[0]->scene.empty());
    for (size_t i = 0; i < games.size(); ++i) {
        INFO(games[i]->name);
        CHECK(config::is_game_name(games[i]->name));
        CHECK(!games[i]->summary.empty());
        CHECK(games::find(games[i]->name) == games[i]);
        for (size_t k = i + 1; k < games.size(); ++k) CHECK(games[k]->name != games[i]->name);
        if (!games[i]->scene.empty()) CHECK(games::scene_by_name(games[i]->scene).has_value());
    }
    CHECK(games::find("asteroids") != nullptr);
    CHECK(games::find("chess") == nullptr);
    CHECK(games::names_list().starts_with("sandbox, "));
}

TEST_CASE("a preset plays the game made for it, else the sandbox", "[games]") {
    CHECK(games::game_for_scene("asteroids") == "asteroids");
    CHECK(games::game_for_scene("platformer") == "sandbox");
    CHECK(games::game_for_scene("no such preset") == "sandbox");
}

TEST_CASE("each game made for a scene is a built-in mode of its name", "[games]") {
    const auto modes = config::builtin_modes();
    CHECK(config::find_mode(modes, "sandbox") != nullptr);
    for (const rules::game_definition* game : games::all()) {
        if (game->scene.empty()) continue;
        const config::mode* m = config::find_mode(modes, std::string(game->name));
        REQUIRE(m != nullptr);
        CHECK(m->world.rules == game->name);
        CHECK(m->preset == game->scene);
    }
}

TEST_CASE("every game makes its rules on its scene with its default parameters", "[games]") {
    for (const rules::game_definition* game : games::all()) {
        INFO(game->name);
        world::world_config c = games::scene_by_name(game->scene.empty() ? "platformer" : game->scene).value();
        c.rules = game->name;
        CHECK(games::config_problem(c).empty());
        world::world w(c, 3);
        const auto r = games::make_rules(w);
        REQUIRE(r != nullptr);
        CHECK(r->has_state() == (game->name != "sandbox"));
    }
}

TEST_CASE("a game this build does not have is refused where it would be played", "[games]") {
    world::world_config c = world::platformer_preset();
    c.rules = "chess";
    const std::string problem = games::config_problem(c);
    CHECK(problem == "rules: unknown game 'chess' (" + games::names_list() + ")");
    world::world w(c, 1);
    CHECK_THROWS_WITH(games::make_rules(w), problem);
}

TEST_CASE("a config naming a game this build lacks still reads, so a client can draw its bodies", "[games]") {
    const auto parsed = config::parse_config_json(R"({"preset": "platformer", "rules": "chess"})");
    REQUIRE(parsed);
    CHECK(parsed.value.rules == "chess");
    CHECK(config::parse_config_json(config::config_to_json(parsed.value)).value.rules == "chess");
    for (const char* bad :
         {R"("Tag")", R"("")", R"("1v1")", R"("tag!")", R"(3)", R"("a_name_of_thirty_three_letters_xx")"}) {
        INFO(bad);
        const auto refused = config::parse_config_json(std::string(R"({"rules": )") + bad + "}");
        REQUIRE(!refused);
        CHECK(refused.error.find("field 'rules' must be a game's name") != std::string::npos);
    }
    CHECK(config::parse_config_json(R"({"rules": "a_name_of_thirty_two_letters_xxx"})"));
}

TEST_CASE("the scenes are the world's presets, then each game's own, made for that game", "[games]") {
    const std::string list = games::scene_names_list();
    CHECK(list.starts_with("asteroids, platformer, pyramid"));
    for (const rules::game_definition* game : games::all()) {
        if (game->scene_world == nullptr) continue;
        INFO(game->name);
        CHECK(list.find(", " + std::string(game->scene)) != std::string::npos);
        const auto scene = games::scene_by_name(game->scene);
        REQUIRE(scene.has_value());
        CHECK(scene->rules == game->name);
        CHECK(games::game_for_scene(game->scene) == game->name);
    }
    CHECK_FALSE(games::scene_by_name("nowhere").has_value());
}
