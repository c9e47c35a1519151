// Asteroids in the registry (server/rules/game.hpp): played on the asteroids scene, with the
// parameters of asteroids_params.hpp.
#include "games/asteroids/asteroids_params.hpp"
#include "games/asteroids/asteroids_rules.hpp"
#include "games/asteroids/asteroids_shot.hpp"
#include "server/rules/game.hpp"

namespace arena::games {

namespace {

std::string params_problem(std::string_view rules_params) {
    return rules::parse_asteroids_params(rules_params).error;
}

std::unique_ptr<rules::rules> make(world::world& w) {
    const auto params = rules::parse_asteroids_params(w.config().rules_params);
    return std::make_unique<rules::asteroids_rules>(w, params.value);
}

std::unique_ptr<rules::shot_rule> make_shot_rule(std::string_view rules_params) {
    const auto params = rules::parse_asteroids_params(rules_params);
    if (!params) return nullptr;
    return std::make_unique<rules::asteroids_shot_rule>(params.value);
}

}  // namespace

extern const rules::game_definition asteroids_game;
const rules::game_definition asteroids_game{
    .name = "asteroids",
    .summary = "bullets, rocks that split, lives and score",
    .scene = "asteroids",
    .scene_world = nullptr,
    .params_problem = params_problem,
    .make = make,
    .make_bot = nullptr,
    .make_shot_rule = make_shot_rule,
};

}  // namespace arena::games
