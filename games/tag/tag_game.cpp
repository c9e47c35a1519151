// Tag in the registry (server/rules/game.hpp): a small walled room of its own, no parameters.
#include "games/tag/tag_rules.hpp"
#include "server/rules/game.hpp"
#include "server/rules/params_reader.hpp"
#include "server/world/presets.hpp"

namespace arena::games {

namespace {

// The asteroids ships in a 60 m room with walls and a few rocks to dodge round.
world::world_config tag_room() {
    world::world_config c = world::asteroids_preset();
    c.boundary = world::boundary::walls;
    c.size = {60, 60};
    c.rocks.count = 6;
    c.rules = "tag";
    return c;
}

// Tag has no parameters: any field is unknown.
std::string no_params(std::string_view rules_params) {
    return rules::read_params_problem(rules_params, [](rules::params_reader&) {});
}

std::unique_ptr<rules::rules> make(world::world& w) {
    return std::make_unique<rules::tag_rules>(w);
}

}  // namespace

extern const rules::game_definition tag_game;
const rules::game_definition tag_game{
    .name = "tag",
    .summary = "one player is it; touching passes it on; least time as it wins",
    .scene = "tag",
    .scene_world = tag_room,
    .params_problem = no_params,
    .make = make,
    .make_bot = nullptr,
};

}  // namespace arena::games
