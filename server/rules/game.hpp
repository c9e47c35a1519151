#pragma once
// What the registry (games/registry.hpp) knows of a game: its name, the scene it is made for,
// how it checks its parameters and how it makes its rules. A game's folder defines one, named
// `NAME_game` in namespace arena::games (games/asteroids/asteroids_game.cpp); the one line
// `arena_game(NAME)` in games/CMakeLists.txt puts it in the registry.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "server/rules/rules.hpp"
#include "server/rules/shot_rule.hpp"
#include "server/world/config.hpp"
#include "server/world/world.hpp"

namespace arena::bots {
class game_bot;  // client_sim/game_bot.hpp
}  // namespace arena::bots

namespace arena::rules {

struct game_definition {
    std::string_view name;     // as a config's "rules" and a mode name it
    std::string_view summary;  // one line for --help: what the game is
    // The scene it is made for: a world preset (world/presets.hpp), or its own (scene_world);
    // "" none. A preset or a mode of this name plays the game on it.
    std::string_view scene;
    // The world of its own scene, when the world's presets have none for it: the game's
    // folder builds it (a pitch, walls and goals); null when `scene` is a world preset.
    world::world_config (*scene_world)() = nullptr;
    // Why `rules_params` (a config's, as canonical JSON text; "" when it has none) do not suit
    // the game: one line naming the field ("rules_params.FIELD must be ..."); "" when they do.
    std::string (*params_problem)(std::string_view rules_params);
    // The game's rules, set up on `w`: a new world built from a config naming this game, whose
    // parameters params_problem accepted.
    std::unique_ptr<rules> (*make)(world::world& w);
    // Its own bot (client_sim/game_bot.hpp), for `arena-bots --behavior game`; null: none.
    std::unique_ptr<bots::game_bot> (*make_bot)(std::uint64_t seed, std::uint32_t index) = nullptr;
    // Its fire rule for the `rules_params` of a world (server/rules/shot_rule.hpp), which clients
    // run to predict their own shots; null when the game's players fire nothing to predict, or
    // when those parameters do not read (then the server's shots are shown as they come).
    std::unique_ptr<shot_rule> (*make_shot_rule)(std::string_view rules_params) = nullptr;
};

}  // namespace arena::rules
