#include "games/registry.hpp"

#include <stdexcept>

#include "games/games_table.hpp"
#include "server/world/presets.hpp"

namespace arena::games {

namespace {

std::string sandbox_params_problem(std::string_view rules_params) {
    if (rules_params.empty() || rules_params == "{}") return "";
    return "rules_params: the sandbox rules take no parameters";
}

std::unique_ptr<rules::rules> make_sandbox(world::world&) {
    return std::make_unique<rules::rules>();
}

}  // namespace

const rules::game_definition sandbox_game{
    .name = "sandbox",
    .summary = "the physics alone: no score",
    .scene = "",
    .scene_world = nullptr,
    .params_problem = sandbox_params_problem,
    .make = make_sandbox,
    .make_bot = nullptr,
};

std::span<const rules::game_definition* const> all() {
    return registered_games();
}

const rules::game_definition* find(std::string_view name) {
    for (const rules::game_definition* g : all())
        if (g->name == name) return g;
    return nullptr;
}

std::string names_list() {
    std::string out;
    for (const rules::game_definition* g : all()) out.append(out.empty() ? "" : ", ").append(g->name);
    return out;
}

std::string described_list() {
    std::string out;
    for (const rules::game_definition* g : all()) {
        out.append(out.empty() ? "" : ", ").append(g->name);
        out.append(" (").append(g->summary).append(")");
    }
    return out;
}

std::string_view game_for_scene(std::string_view scene) {
    for (const rules::game_definition* g : all())
        if (!g->scene.empty() && g->scene == scene) return g->name;
    return sandbox_game.name;
}

std::optional<world::world_config> scene_by_name(std::string_view name) {
    if (auto preset = world::preset_by_name(name)) return preset;
    for (const rules::game_definition* g : all())
        if (g->scene_world != nullptr && g->scene == name) return g->scene_world();
    return std::nullopt;
}

std::string scene_names_list() {
    std::string out;
    for (const std::string_view name : world::preset_names()) out.append(out.empty() ? "" : ", ").append(name);
    for (const rules::game_definition* g : all())
        if (g->scene_world != nullptr) out.append(", ").append(g->scene);
    return out;
}

std::string config_problem(const world::world_config& config) {
    const rules::game_definition* game = find(config.rules);
    if (game == nullptr) return "rules: unknown game '" + config.rules + "' (" + names_list() + ")";
    return game->params_problem(config.rules_params);
}

std::unique_ptr<rules::rules> make_rules(world::world& w) {
    if (std::string problem = config_problem(w.config()); !problem.empty()) throw std::invalid_argument(problem);
    return find(w.config().rules)->make(w);
}

}  // namespace arena::games
