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
// with high drag, static platforms and a ramp, crates to push and stand on, a stack of crates.
world_config platformer_preset();

// Box2D's pyramid benchmark: a triangle of 1 m boxes, `base` in its bottom row (base·(base+1)/2
// boxes), standing on a static ground segment; gravity, no walls. Box2D calls base 100
// large_pyramid.
world_config pyramid_preset(uint32_t base = 20);

// The world of a preset by its name. Its `rules` is the sandbox's, as every preset function's
// above: tests and benchmarks take the physics alone. A preset is a scene; a game names the
// scene it is made for (games/registry.hpp).
std::optional<world_config> preset_by_name(std::string_view name);
std::vector<std::string_view> preset_names();

}  // namespace arena::world
