#pragma once
// A game's own bot: a behaviour that knows the game's rules, kept in the game's folder
// (games/soccer/soccer_bot.cpp) and made through its definition (server/rules/game.hpp,
// make_bot). `arena-bots --behavior game` plays it; a game without one is played by seek.
// Like every behaviour it is a pure function of what it sees: the same views give the same
// inputs on every machine (only + − × ÷, sqrt and the world's own cos/sin).
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <span>

#include "protocol/arena_generated.h"
#include "protocol/manifest.hpp"
#include "server/world/body.hpp"
#include "server/world/config.hpp"
#include "server/world/input.hpp"

namespace arena::bots {

// What a game's bot sees on a tick.
struct game_view {
    const world::body* own = nullptr;             // its body as predicted; null until placed
    std::span<const protocol::BodyState> bodies;  // the newest snapshot's, by increasing id
    std::uint32_t player = 0;                     // its player id
    const world::world_config* config = nullptr;  // the world it plays in
    const protocol::game_manifest* game = nullptr;
    // Every player's declared values (the manifest's player_fields order), by player id.
    const std::map<std::uint32_t, std::array<std::int32_t, protocol::max_game_fields>>* values = nullptr;
    // BodyShape.kind of body `id` (0: a plain body, or its shape not held).
    std::function<std::uint8_t(std::uint32_t)> kind_of;
};

class game_bot {
public:
    virtual ~game_bot() = default;
    // The input for the next tick: thrust and turn finite, in [−1, 1].
    virtual world::player_input next(const game_view& seen) = 0;
};

}  // namespace arena::bots
