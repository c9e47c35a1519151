#include "server/config/world_choice.hpp"

#include "server/rules/rules.hpp"
#include "server/world/presets.hpp"

namespace arena::config {

result<world_choice> choose_world(const std::string& preset, const std::string& config_file, const std::string& rules) {
    using choice = result<world_choice>;
    world_choice chosen;
    if (!config_file.empty()) {
        auto loaded = load_config_file(config_file);
        if (!loaded) return choice::failure(std::move(loaded.error));
        chosen.config = std::move(loaded.value);
    } else {
        auto world = world::preset_by_name(preset);
        if (!world) return choice::failure("--preset: unknown preset '" + preset + "' (asteroids, platformer)");
        chosen.config = std::move(*world);
        // `--preset asteroids` used to play the sandbox's rules: rocks, but no bullets or score.
        chosen.config.rules = *world::preset_rules(preset);
        chosen.preset = preset;
    }
    if (!rules.empty()) {
        const auto named = rules_by_name(rules);
        if (!named) return choice::failure("--rules: unknown rules '" + rules + "' (" + rules_names_list() + ")");
        chosen.config.rules = *named;
    }
    // The game checks its parameters once the game is settled (--rules may change it).
    if (std::string problem = rules::rules_params_problem(chosen.config); !problem.empty()) {
        if (!config_file.empty()) problem = config_file + ": " + problem;
        return choice::failure(std::move(problem));
    }
    return choice::success(std::move(chosen));
}

}  // namespace arena::config
