#include "server/config/modes.hpp"

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "games/registry.hpp"
#include "server/config/config_json.hpp"

namespace arena::config {

using nlohmann::json;

namespace {

mode preset_mode(std::string name, const std::string& preset) {
    mode m;
    m.name = std::move(name);
    m.world = *games::scene_by_name(preset);
    m.world.rules = games::game_for_scene(preset);
    m.preset = preset;
    return m;
}

// One entry of "modes"; an error names its field.
result<mode> parse_mode(const json& entry) {
    using out = result<mode>;
    if (!entry.is_object()) return out::failure("is not an object");
    mode m;
    for (const auto& [key, value] : entry.items()) {
        if (key == "name") {
            if (!value.is_string()) return out::failure("name: not a string");
            m.name = value.get<std::string>();
        } else if (key == "preset") {
            if (!value.is_string()) return out::failure("preset: not a string");
            m.preset = value.get<std::string>();
        } else if (key == "max_players") {
            if (!value.is_number_unsigned() || value.get<uint64_t>() < 1 || value.get<uint64_t>() > 100'000)
                return out::failure("max_players: not a whole number in [1, 100000]");
            m.max_players = value.get<uint32_t>();
        } else if (key == "duration") {
            if (!value.is_number() || !(value.get<double>() >= 0) || value.get<double>() > 86'400 * 7)
                return out::failure("duration: not a number of seconds in [0, 604800]");
            m.duration_s = value.get<double>();
        } else if (key != "world" && key != "rules") {
            return out::failure("unknown field '" + key + "'");
        }
    }
    if (!valid_mode_name(m.name))
        return out::failure("name: 1 to 32 of a-z, 0-9, '_' and '-' (got '" + m.name.substr(0, 40) + "')");
    if (!m.preset.empty() && !games::scene_by_name(m.preset))
        return out::failure("preset: unknown preset '" + m.preset + "' (" + games::scene_names_list() + ")");
    if (!entry.contains("world") && m.preset.empty()) return out::failure("needs a preset or a world");
    json world_json = entry.contains("world") ? entry["world"] : json::object();
    if (!world_json.is_object()) return out::failure("world: not an object");
    const bool world_names_rules = world_json.contains("rules");
    if (!m.preset.empty() && !world_json.contains("preset")) world_json["preset"] = m.preset;
    auto world = parse_config_json(world_json.dump());
    if (!world) return out::failure("world: " + world.error);
    m.world = std::move(world.value);
    // A preset plays its own game unless the world or "rules" says otherwise.
    if (!m.preset.empty() && !world_names_rules) m.world.rules = games::game_for_scene(m.preset);
    if (entry.contains("rules")) {
        const json& rules = entry["rules"];
        if (!rules.is_string() || games::find(rules.get<std::string>()) == nullptr)
            return out::failure("rules: not one of " + games::names_list());
        m.world.rules = rules.get<std::string>();
    }
    if (const std::string problem = games::config_problem(m.world); !problem.empty())
        return out::failure("world: " + problem);
    return out::success(std::move(m));
}

}  // namespace

bool valid_mode_name(std::string_view name) {
    if (name.empty() || name.size() > max_mode_name_bytes) return false;
    for (const char c : name)
        if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-')) return false;
    return true;
}

std::vector<mode> builtin_modes() {
    // The sandbox on the platformer, then each game made for a scene, named as the game.
    std::vector<mode> modes{preset_mode("sandbox", "platformer")};
    for (const rules::game_definition* game : games::all()) {
        if (!game->scene.empty()) modes.push_back(preset_mode(std::string(game->name), std::string(game->scene)));
    }
    return modes;
}

result<std::vector<mode>> parse_modes_json(std::string_view text) {
    using out = result<std::vector<mode>>;
    if (text.size() > max_modes_file_bytes)
        return out::failure("larger than " + std::to_string(max_modes_file_bytes) + " bytes");
    json doc = json::parse(text, nullptr, false);
    if (doc.is_discarded()) return out::failure("not valid JSON");
    if (!doc.is_object() || !doc.contains("modes") || !doc["modes"].is_array())
        return out::failure("needs an object with a \"modes\" array");
    for (const auto& [key, value] : doc.items())
        if (key != "modes") return out::failure("unknown field '" + key + "'");
    const json& list = doc["modes"];
    if (list.size() > max_modes) return out::failure("more than " + std::to_string(max_modes) + " modes");
    std::vector<mode> modes;
    for (size_t i = 0; i < list.size(); ++i) {
        auto m = parse_mode(list[i]);
        if (!m) return out::failure("modes[" + std::to_string(i) + "]: " + m.error);
        if (find_mode(modes, m.value.name))
            return out::failure("modes[" + std::to_string(i) + "]: a second mode named '" + m.value.name + "'");
        modes.push_back(std::move(m.value));
    }
    return out::success(std::move(modes));
}

result<std::vector<mode>> load_modes_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return result<std::vector<mode>>::failure(path + ": cannot be read");
    std::ostringstream text;
    text << in.rdbuf();
    auto modes = parse_modes_json(text.str());
    if (!modes) return result<std::vector<mode>>::failure(path + ": " + modes.error);
    return modes;
}

std::vector<mode> merge_modes(std::vector<mode> base, const std::vector<mode>& more) {
    for (const mode& m : more) {
        auto same = std::find_if(base.begin(), base.end(), [&](const mode& b) { return b.name == m.name; });
        if (same != base.end()) {
            *same = m;
        } else {
            base.push_back(m);
        }
    }
    return base;
}

const mode* find_mode(const std::vector<mode>& modes, std::string_view name) {
    for (const mode& m : modes)
        if (m.name == name) return &m;
    return nullptr;
}

std::string mode_names(const std::vector<mode>& modes) {
    std::string out;
    for (const mode& m : modes) out += (out.empty() ? "" : ", ") + m.name;
    return out;
}

}  // namespace arena::config
