// Soccer in the registry (server/rules/game.hpp): played on its own pitch (soccer_pitch.hpp),
// with the parameters of soccer_params.hpp.
#include "games/soccer/soccer_bot.hpp"
#include "games/soccer/soccer_params.hpp"
#include "games/soccer/soccer_pitch.hpp"
#include "games/soccer/soccer_rules.hpp"
#include "server/rules/game.hpp"

namespace arena::games {

namespace {

std::string params_problem(std::string_view rules_params) {
    return rules::parse_soccer_params(rules_params).error;
}

std::unique_ptr<rules::rules> make(world::world& w) {
    const auto params = rules::parse_soccer_params(w.config().rules_params);
    return std::make_unique<rules::soccer_rules>(w, params.value);
}

}  // namespace

extern const rules::game_definition soccer_game;
const rules::game_definition soccer_game{
    .name = "soccer",
    .summary = "two teams, a ball, a kick button, goals and a match clock",
    .scene = "soccer",
    .scene_world = rules::soccer_pitch,
    .params_problem = params_problem,
    .make = make,
    .make_bot = rules::make_soccer_bot,
};

}  // namespace arena::games
