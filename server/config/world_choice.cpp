#include "server/config/world_choice.hpp"

#include "games/registry.hpp"

namespace arena::config {

result<world_choice> choose_world(const std::string& preset, const std::string& config_file, const std::string& rules) {
    using choice = result<world_choice>;
    world_choice chosen;
    if (!config_file.empty()) {
        auto loaded = load_config_file(config_file);
        if (!loaded) return choice::failure(std::move(loaded.error));
        chosen.config = std::move(loaded.value);
    } else {
        auto world = games::scene_by_name(preset);
        if (!world)
            return choice::failure("--preset: unknown preset '" + preset + "' (" + games::scene_names_list() + ")");
        chosen.config = std::move(*world);
        // A preset plays the game made for it (`--preset asteroids` used to play the sandbox's
        // rules: rocks, but no bullets or score).
        chosen.config.rules = games::game_for_scene(preset);
        chosen.preset = preset;
    }
    if (!rules.empty()) {
        if (games::find(rules) == nullptr)
            return choice::failure("--rules: unknown rules '" + rules + "' (" + games::names_list() + ")");
        chosen.config.rules = rules;
    }
    // The game checks its parameters once the game is settled (--rules may change it).
    if (std::string problem = games::config_problem(chosen.config); !problem.empty()) {
        if (!config_file.empty()) problem = config_file + ": " + problem;
        return choice::failure(std::move(problem));
    }
    return choice::success(std::move(chosen));
}

}  // namespace arena::config
