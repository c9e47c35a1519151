#include "server/config/world_choice.hpp"

#include "server/world/presets.hpp"

namespace arena::config {

std::variant<world_choice, config_error> choose_world(const std::string& preset, const std::string& config_file,
                                                      const std::string& rules) {
    world_choice chosen;
    if (!config_file.empty()) {
        auto loaded = load_config_file(config_file);
        if (auto* e = std::get_if<config_error>(&loaded)) return *e;
        chosen.config = std::get<world::world_config>(std::move(loaded));
    } else {
        auto world = world::preset_by_name(preset);
        if (!world) return config_error{"--preset: unknown preset '" + preset + "' (asteroids, platformer)"};
        chosen.config = std::move(*world);
        // `--preset asteroids` used to play the sandbox's rules: rocks, but no bullets or score.
        chosen.config.rules = *world::preset_rules(preset);
        chosen.preset = preset;
    }
    if (!rules.empty()) {
        const auto named = rules_by_name(rules);
        if (!named) return config_error{"--rules: unknown rules '" + rules + "' (" + rules_names_list() + ")"};
        chosen.config.rules = *named;
    }
    return chosen;
}

}  // namespace arena::config
