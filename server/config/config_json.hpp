#pragma once
// World configs as JSON text: the format of --config files and of Welcome.world_config.
// Every field is optional (missing fields keep their defaults, or the named preset's); an
// unknown field, a wrong type, a non-finite number or a value outside the field's interval is
// an error naming the field.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "server/world/config.hpp"
#include "server/world/result.hpp"

namespace arena::config {

// Bounds on a config's size. Its JSON travels in every Welcome, which a client accepts up to
// protocol::max_server_frame_body (16 MiB): 400 000 fluid regions once made a 54 MB Welcome.
// With at most max_fluid_regions regions, config_to_json() stays under 64 KiB whatever the
// values (tests/config/config_limits_tests.cpp builds the largest); a text longer than
// max_config_bytes is refused before it is parsed.
inline constexpr size_t max_fluid_regions = 256;
inline constexpr size_t max_config_bytes = 1 << 20;
// Worlds up to 1000 km a side: positions are quantised to ±8 388 km on the wire
// (protocol/delta/quantize.hpp), and every body fits the delta decoder's 2^20.
inline constexpr double max_world_size = 1e6;  // m
inline constexpr uint32_t max_world_bodies = 1u << 20;
// Sub-steps per step (world_config::substeps): Box2D v3 uses 4; beyond 8 a step costs more
// than it gains.
inline constexpr uint32_t max_substeps = 8;

// Parses JSON text; `{"preset": "platformer", "gravity": [0, -3]}` starts from a preset.
result<world::world_config> parse_config_json(std::string_view text);

// Reads and parses a file; errors name the file.
result<world::world_config> load_config_file(const std::string& path);

// A config's "rules" is a game's name: a lower case letter, then up to 31 lower case letters,
// digits or '_' (the names cmake/games.cmake accepts). Which names this build plays is the
// registry's to say (games/registry.hpp).
inline constexpr size_t max_game_name = 32;
bool is_game_name(std::string_view name);

// Every field, so that parse_config_json(config_to_json(c)) == c bit for bit.
std::string config_to_json(const world::world_config& config);

}  // namespace arena::config
