#pragma once
// Everything that changes a world in one tick besides time itself: who joined, who left, and
// the input each player's body consumed. The match applies ticks through apply_tick, and a
// replay applies the recorded ticks through the same function, so the two cannot drift apart.
#include <cstdint>
#include <string>
#include <vector>

#include "server/rules/rules.hpp"
#include "server/world/input.hpp"
#include "server/world/world.hpp"

namespace arena::match {

struct tick_record {
    uint32_t tick = 0;                    // the world's tick before this step
    std::vector<world::player_id> joins;  // owners, spawned in this order
    std::vector<world::body_id> leaves;   // bodies removed, in this order
    world::tick_inputs inputs;            // one per player body that consumed an input
    // The name of each join, in the order of `joins` (for the recording: a replayed scoreboard
    // names its players); empty from a recording that holds no names. The world ignores it.
    std::vector<std::string> join_names;
};

// Joins (world::spawn_player), then leaves (world::remove_body), then one step with the inputs.
// Returns the body id spawned for each join, in order (none, 0, when the world was full).
std::vector<world::body_id> apply_tick(world::world& w, const tick_record& record);
// The same under game rules (server/rules/rules.hpp): the joins' bodies and the leaves go to
// the rules first, the rules see the inputs before the step and the contact events after it.
// The match and the replay both call this, so the rules' state replays bit for bit.
std::vector<world::body_id> apply_tick(world::world& w, rules::rules& r, const tick_record& record);

}  // namespace arena::match
