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
// made before names were recorded holds player ids alone).
std::string scoreboard_json(std::span<const rules::score_line> lines, std::span<const std::string> names = {});

}  // namespace arena::config
