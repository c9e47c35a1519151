#pragma once
// Modes: what a match plays. A mode names a world (a preset or a config), its game rules, a
// player capacity and an optional duration; a client asks for one by name (Hello.mode, the
// lobby's POST /matches) and the server joins it to a match of that mode or creates one.
// Built in: sandbox, and one per game made for a scene. --modes FILE adds modes or overrides them by name.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "server/world/config.hpp"
#include "server/world/result.hpp"

namespace arena::config {

inline constexpr size_t max_mode_name_bytes = 32;  // [a-z0-9_-], 1 to 32 characters
inline constexpr size_t max_modes = 64;            // in one --modes file
inline constexpr size_t max_modes_file_bytes = 4 << 20;

struct mode {
    std::string name;
    world::world_config world;
    std::string preset;        // the preset it starts from (Welcome.preset); "" for a config of its own
    uint32_t max_players = 0;  // a match's capacity; 0: the server's --max-players
    double duration_s = 0;     // a match of this mode ends this long after it starts; 0: no limit
};

// Whether `name` may name a mode: 1 to max_mode_name_bytes of [a-z0-9_-].
bool valid_mode_name(std::string_view name);

// The modes every server plays: "sandbox" (the platformer preset, sandbox rules), then one for
// each registered game made for a preset, named as the game ("asteroids": its preset and rules).
std::vector<mode> builtin_modes();

// A --modes file's text: {"modes": [{"name": "duel", "preset": "asteroids", "rules": "asteroids",
// "world": {...a world config...}, "max_players": 2, "duration": 120}, ...]}. "world" is a world
// config as --config reads it (over "preset" when both are given); "rules" overrides the
// world's (else a preset's own rules). An error names the mode and its field.
result<std::vector<mode>> parse_modes_json(std::string_view text);
// The same from a file; errors name the file.
result<std::vector<mode>> load_modes_file(const std::string& path);

// `base` with each of `more` added, or replacing the mode of the same name.
std::vector<mode> merge_modes(std::vector<mode> base, const std::vector<mode>& more);
// The mode called `name` in `modes`, or nullptr.
const mode* find_mode(const std::vector<mode>& modes, std::string_view name);
// Their names, for a message: "sandbox, asteroids".
std::string mode_names(const std::vector<mode>& modes);

}  // namespace arena::config
