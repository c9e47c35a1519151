#pragma once
// Which recordings of older physics this build still replays bit for bit. A version bump
// changes what some worlds do, not always every world: version 3 changed only chains and
// version 4 only sub-stepped worlds, so a version-2 recording of a world with neither steps here
// exactly as it did when recorded, and refusing it would lose a replayable file for nothing.
#include <cstdint>
#include <string>

#include "server/world/config.hpp"

namespace arena::world {

// The oldest world_version (world.hpp) whose recordings may still replay here.
inline constexpr uint32_t oldest_replayable_world_version = 2;

// What a world of `config` uses that steps differently here than under world version
// `recorded` (in [oldest_replayable_world_version, world_version]), in words for a message;
// empty when it steps the same.
std::string changed_since(uint32_t recorded, const world_config& config);

}  // namespace arena::world
