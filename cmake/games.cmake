# Games as plugins (docs/GAMES.md). A game is a folder games/NAME/ and one line in
# games/CMakeLists.txt:
#
#   arena_game(asteroids)
#
# builds games/NAME/*.cpp into arena_game_NAME, puts the `NAME_game` it defines
# (server/rules/game.hpp) in the registry's table, and, when the tests are built, makes
# games/NAME/tests/*.cpp the test binary game_NAME_tests (tests/CMakeLists.txt). Every header
# of the folder is public: its bots, its tests and a client predicting it may include them.
function(arena_game name)
  if(NOT name MATCHES "^[a-z][a-z0-9_]*$")
    message(FATAL_ERROR "arena_game: '${name}' is not a game name (lower case letters, digits, _)")
  endif()
  set(folder ${CMAKE_CURRENT_SOURCE_DIR}/${name})
  file(GLOB sources CONFIGURE_DEPENDS ${folder}/*.cpp)
  file(GLOB headers CONFIGURE_DEPENDS RELATIVE ${folder} ${folder}/*.hpp)
  if(NOT sources)
    message(FATAL_ERROR "arena_game: games/${name}/ has no .cpp file")
  endif()
  add_library(arena_game_${name} STATIC ${sources})
  target_link_libraries(arena_game_${name} PUBLIC arena_rules arena_world PRIVATE nlohmann_json::nlohmann_json)
  if(headers)
    arena_public_headers(FOLDER games/${name} HEADERS ${headers})
  endif()
  set_property(GLOBAL APPEND PROPERTY ARENA_GAMES ${name})
endfunction()

# The registry (games/registry.cpp) over a table of every game arena_game() registered; call it
# once, after the arena_game lines.
function(arena_games_registry)
  get_property(games GLOBAL PROPERTY ARENA_GAMES)
  set(declarations "")
  set(entries "&sandbox_game")
  set(libraries "")
  foreach(game IN LISTS games)
    string(APPEND declarations "extern const rules::game_definition ${game}_game;\n")
    string(APPEND entries ", &${game}_game")
    list(APPEND libraries arena_game_${game})
  endforeach()
  set(table ${CMAKE_CURRENT_BINARY_DIR}/games_table.cpp)
  file(CONFIGURE OUTPUT ${table} CONTENT
"// Written by cmake/games.cmake from games/CMakeLists.txt: edit that file, not this one.
#include \"games/games_table.hpp\"

namespace arena::games {

${declarations}
std::span<const rules::game_definition* const> registered_games() {
    static const rules::game_definition* const table[] = {${entries}};
    return table;
}

}  // namespace arena::games
")
  add_library(arena_games STATIC ${CMAKE_CURRENT_SOURCE_DIR}/registry.cpp ${table})
  target_link_libraries(arena_games PUBLIC arena_rules arena_world ${libraries})
  arena_public_headers(FOLDER games HEADERS registry.hpp)
endfunction()
