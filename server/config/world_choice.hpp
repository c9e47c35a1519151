#pragma once
// Which world and which game arena-server runs, from its --preset, --config and --rules flags:
// a config file's world (and its "rules", else the sandbox's), or else the preset's world with
// the rules the preset is made for; --rules, when given, overrides either.
#include <string>

#include "server/config/config_json.hpp"
#include "server/world/config.hpp"

namespace arena::config {

struct world_choice {
    world::world_config config;
    std::string preset;  // the preset's name, "" for a config file (Welcome.preset, the replay header)
};

// `config_file` "" uses `preset`; `rules` "" keeps the preset's or the config's. An error is
// one line naming the flag (or the file and its field).
result<world_choice> choose_world(const std::string& preset, const std::string& config_file, const std::string& rules);

}  // namespace arena::config
