#pragma once
// The games this build knows, by name: the sandbox (no score), then every game
// games/CMakeLists.txt registers with `arena_game(NAME)`, in that order. What a match, a replay
// or a config check asks of a game goes through here; nothing outside games/ names one.
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "server/rules/game.hpp"
#include "server/rules/rules.hpp"
#include "server/world/config.hpp"
#include "server/world/world.hpp"

namespace arena::games {

// Every game, the sandbox first.
std::span<const rules::game_definition* const> all();
// The game named `name`, or null.
const rules::game_definition* find(std::string_view name);
// Their names, for a message: "sandbox, asteroids".
std::string names_list();
// Their names with their summaries, for --help: "sandbox (the physics alone: no score), ...".
std::string described_list();
// The game a scene is made for: the first game whose scene it is, else the sandbox.
std::string_view game_for_scene(std::string_view scene);
// The world of scene `name`: a world preset (world/presets.hpp), else a game's own scene; none
// when neither has that name.
std::optional<world::world_config> scene_by_name(std::string_view name);
// Every scene's name, for a message: "asteroids, platformer, pyramid, soccer".
std::string scene_names_list();

// Why `config` cannot be played ("" when it can): its game is not in this build ("rules:
// unknown game 'x' (sandbox, asteroids)"), or its game refuses its rules_params (the sandbox
// takes none but "{}").
std::string config_problem(const world::world_config& config);

// The rules of the game `w`'s config names, set up on `w` (a new world built from that
// config). Throws std::invalid_argument with config_problem's line when it is not "".
std::unique_ptr<rules::rules> make_rules(world::world& w);

}  // namespace arena::games
