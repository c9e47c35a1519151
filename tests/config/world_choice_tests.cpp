// arena-server's choice of world and game from --preset, --config and --rules
// (server/config/world_choice.cpp): a preset plays the rules it is made for.
#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>
#include <string>
#include <variant>

#include "games/registry.hpp"
#include "server/config/world_choice.hpp"
#include "server/world/presets.hpp"

using namespace arena;

namespace {

config::world_choice chosen(const std::string& preset, const std::string& file, const std::string& rules) {
    auto r = config::choose_world(preset, file, rules);
    if (!r) FAIL(r.error);
    return r.value;
}

std::string error_of(const std::string& preset, const std::string& file, const std::string& rules) {
    auto r = config::choose_world(preset, file, rules);
    REQUIRE(!r.ok());
    return r.error;
}

}  // namespace

TEST_CASE("the asteroids preset (--preset asteroids) plays the asteroids rules, not the sandbox's",
          "[config][preset]") {
    // It played the sandbox: rocks, but no bullets, score or scoreboard.
    const config::world_choice c = chosen("asteroids", "", "");
    CHECK(c.config.rules == "asteroids");
    CHECK(c.preset == "asteroids");
    CHECK(c.config.rocks.count == world::asteroids_preset().rocks.count);
    CHECK(chosen("platformer", "", "").config.rules == "sandbox");
    CHECK(chosen("pyramid", "", "").config.rules == "sandbox");
    CHECK(games::game_for_scene("asteroids") == "asteroids");
    CHECK(games::game_for_scene("no such preset") == "sandbox");
}

TEST_CASE("the --rules flag overrides the rules of the preset and of a config file", "[config][preset]") {
    CHECK(chosen("asteroids", "", "sandbox").config.rules == "sandbox");
    CHECK(chosen("platformer", "", "asteroids").config.rules == "asteroids");
    const std::string file = "world_choice_tests_config.json";
    std::ofstream(file) << R"({"preset": "asteroids", "rules": "asteroids", "gravity": [0, -1]})";
    const config::world_choice from_file = chosen("platformer", file, "");
    CHECK(from_file.config.rules == "asteroids");
    CHECK(from_file.config.gravity.y() == -1);
    CHECK(from_file.preset.empty());
    CHECK(chosen("asteroids", file, "sandbox").config.rules == "sandbox");
    // A config file without "rules" is a sandbox, whatever preset it starts from.
    std::ofstream(file) << R"({"preset": "asteroids"})";
    CHECK(chosen("asteroids", file, "").config.rules == "sandbox");
    std::remove(file.c_str());
}

TEST_CASE("an unknown preset or rules name is one line naming the flag", "[config][preset]") {
    CHECK(error_of("tetris", "", "") == "--preset: unknown preset 'tetris' (" + games::scene_names_list() + ")");
    CHECK(error_of("asteroids", "", "chess") == "--rules: unknown rules 'chess' (" + games::names_list() + ")");
    CHECK(error_of("asteroids", "no/such/file.json", "").find("no/such/file.json: cannot open") == 0);
}

TEST_CASE("a config's game parameters are checked once --rules has settled the game", "[config][params]") {
    const std::string file = "world_choice_tests_params.json";
    std::ofstream(file) << R"({"preset": "asteroids", "rules": "asteroids", "rules_params": {"lives": 1}})";
    CHECK(chosen("asteroids", file, "").config.rules_params == R"({"lives":1})");
    // The same parameters under the sandbox rules, which take none.
    CHECK(error_of("asteroids", file, "sandbox") == file + ": rules_params: the sandbox rules take no parameters");
    std::ofstream(file) << R"({"preset": "asteroids", "rules": "asteroids", "rules_params": {"lives": 1001}})";
    CHECK(error_of("asteroids", file, "") == file + ": rules_params.lives must be a whole number in [0, 1000]");
    std::remove(file.c_str());
}
