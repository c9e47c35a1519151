#pragma once
// World configs as JSON text: the format of --config files and of Welcome.world_config.
// Every field is optional (missing fields keep their defaults, or the named preset's); an
// unknown field, a wrong type or a non-finite number is an error naming the field.
#include <string>
#include <string_view>
#include <variant>

#include "server/world/config.hpp"

namespace arena::config {

struct config_error {
    std::string message;  // one line: what is wrong and where
};

// Parses JSON text; `{"preset": "platformer", "gravity": [0, -3]}` starts from a preset.
std::variant<world::world_config, config_error> parse_config_json(std::string_view text);

// Reads and parses a file; errors name the file.
std::variant<world::world_config, config_error> load_config_file(const std::string& path);

// Every field, so that parse_config_json(config_to_json(c)) == c bit for bit.
std::string config_to_json(const world::world_config& config);

}  // namespace arena::config
