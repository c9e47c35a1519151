// --modes files (server/config/modes.*): the built-in modes, what a file may say, and the
// one-line errors that name the mode and its field.
#include <catch2/catch.hpp>

#include "games/registry.hpp"
#include "server/config/modes.hpp"
#include "server/world/presets.hpp"

using namespace arena;

TEST_CASE("the built-in modes are sandbox and one per game made for a scene, each with its game", "[config][modes]") {
    const auto modes = config::builtin_modes();
    // Every game of this build has a scene: the modes are the registry's games, in its order.
    REQUIRE(config::mode_names(modes) == games::names_list());
    CHECK(config::find_mode(modes, "asteroids")->world.rules == "asteroids");
    CHECK(config::find_mode(modes, "sandbox")->world.rules == "sandbox");
    CHECK(config::find_mode(modes, "sandbox")->preset == "platformer");
    CHECK(config::find_mode(modes, "chess") == nullptr);
}

TEST_CASE("a modes file adds modes from a preset or a world, and overrides by name", "[config][modes]") {
    auto parsed = config::parse_modes_json(R"({"modes": [
        {"name": "duel", "preset": "asteroids", "max_players": 2, "duration": 120},
        {"name": "floaty", "world": {"preset": "platformer", "gravity": [0, -3]}, "rules": "asteroids"},
        {"name": "sandbox", "preset": "asteroids", "rules": "sandbox"}]})");
    REQUIRE(parsed);
    const auto& m = parsed.value;
    REQUIRE(m.size() == 3);
    CHECK(m[0].max_players == 2);
    CHECK(m[0].duration_s == 120);
    CHECK(m[0].world.rules == "asteroids");  // the preset's own game
    CHECK(m[1].world.gravity.y() == Approx(-3));
    CHECK(m[1].world.rules == "asteroids");
    const auto merged = config::merge_modes(config::builtin_modes(), m);
    CHECK(config::mode_names(merged) == games::names_list() + ", duel, floaty");
    CHECK(config::find_mode(merged, "sandbox")->preset == "asteroids");  // overridden
}

TEST_CASE("a bad modes file is refused with the mode and the field", "[config][modes]") {
    auto error_of = [](std::string_view text) {
        auto r = config::parse_modes_json(text);
        REQUIRE_FALSE(r);
        return r.error;
    };
    CHECK(error_of("[]") == "needs an object with a \"modes\" array");
    CHECK(error_of("{") == "not valid JSON");
    CHECK(error_of(R"({"modes": [{"name": "Duel!", "preset": "asteroids"}]})").find("modes[0]: name:") == 0);
    CHECK(error_of(R"({"modes": [{"name": "a", "preset": "nowhere"}]})") ==
          "modes[0]: preset: unknown preset 'nowhere' (" + games::scene_names_list() + ")");
    CHECK(error_of(R"({"modes": [{"name": "a"}]})") == "modes[0]: needs a preset or a world");
    CHECK(error_of(R"({"modes": [{"name": "a", "preset": "asteroids", "teams": 2}]})") ==
          "modes[0]: unknown field 'teams'");
    CHECK(error_of(R"({"modes": [{"name": "a", "preset": "asteroids", "max_players": 0}]})").find("max_players") !=
          std::string::npos);
    CHECK(error_of(R"({"modes": [{"name": "a", "world": {"gravity": [0, "down"]}}]})").find("modes[0]: world:") == 0);
    CHECK(error_of(R"({"modes": [{"name": "a", "preset": "asteroids"}, {"name": "a", "preset": "asteroids"}]})") ==
          "modes[1]: a second mode named 'a'");
    CHECK(error_of(R"({"modes": [{"name": "a", "preset": "asteroids", "rules": "chess"}]})").find("rules:") !=
          std::string::npos);
}
