#pragma once
// The table of games, which the build writes from games/CMakeLists.txt's `arena_game` lines
// (cmake/games.cmake): the sandbox, then each game's `NAME_game` in the order of those lines.
#include <span>

#include "server/rules/game.hpp"

namespace arena::games {

extern const rules::game_definition sandbox_game;  // registry.cpp
std::span<const rules::game_definition* const> registered_games();

}  // namespace arena::games
