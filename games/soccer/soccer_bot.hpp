#pragma once
// Soccer's bot (client_sim/game_bot.hpp): the player of its team nearest the ball goes behind
// it and kicks, shooting at the other goal when it is near or no team-mate is ahead, else
// passing to the team-mate furthest ahead; the others spread out ahead of the ball, one stays
// back between the ball and its own goal.
#include <cstdint>
#include <memory>

#include "client_sim/game_bot.hpp"

namespace arena::rules {

std::unique_ptr<bots::game_bot> make_soccer_bot(std::uint64_t seed, std::uint32_t index);

// A player's input that turns it towards `target` and runs when it faces it (the bot's steering,
// and the scripted matches' in the tests).
world::player_input run_to(const world::body& own, const world::vec2& target);

}  // namespace arena::rules
