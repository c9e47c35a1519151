#pragma once
// Named starting configs. Together they exercise every force of the lecture.
#include <optional>
#include <string_view>
#include <vector>

#include "server/world/config.hpp"

namespace arena::world {

// Asteroids: no gravity, wrap-around, thrust and turn, light air drag, drifting rocks.
world_config asteroids_preset();
// Platformer: gravity, walls with a frictional floor, running and jumping, a pool of water
// with high drag.
world_config platformer_preset();

std::optional<world_config> preset_by_name(std::string_view name);
std::vector<std::string_view> preset_names();

}  // namespace arena::world
