#pragma once
// The game's scoreboard as JSON, one writer for every place that prints it (arena-server's
// --stats-json, arena-replay --scoreboard), so that a live scoreboard and a replayed one
// compare as text: [{"player": 1, "name": "ada", "score": 70, "kills": 0, "deaths": 1,
// "shots": 12, "hits": 3}, ...] in player id order.
#include <span>
#include <string>

#include "server/rules/rules.hpp"

namespace arena::config {

// `names[k]` is the name of `lines[k]`'s player; missing names are written as "" (a recording
// made before names were recorded holds player ids alone). With the game's manifest, each line
// also holds the game's declared fields by their names ("goals": 2), beside the protocol's own
// (a name they share is left as the protocol's).
std::string scoreboard_json(std::span<const rules::score_line> lines, std::span<const std::string> names = {},
                            const protocol::game_manifest* game = nullptr);

}  // namespace arena::config
