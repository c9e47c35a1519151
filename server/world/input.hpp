#pragma once
// A player's input for one tick, and its check at the boundary of the world: non-finite values
// are refused (NaN must never enter the state), out-of-range values are clamped.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "server/world/ids.hpp"
#include "server/world/types.hpp"

namespace arena::world {

struct player_input {
    real thrust = 0.0f;   // [−1, 1], share of control.thrust_force
    real turn = 0.0f;     // [−1, 1], share of control.turn_torque (positive: counter-clockwise)
    uint8_t buttons = 0;  // bit 0: impulse (boost or jump)
    // Lag compensation (docs/LAG_COMPENSATION.md): how far behind the tick it is applied in the
    // world the player saw was when making this input, in 1/256 ticks, as the match clamped
    // it (0: judged against the present). The world's step ignores it; a game's rules may
    // judge this player's shots against the past it saw.
    uint16_t rewind = 0;
};

// The most a match rewinds (1/256 ticks): 64 ticks, a second at 64 Hz. Games keep their history
// of hittable bodies this deep (server/rules/hit_history.hpp).
inline constexpr uint16_t max_rewind = 64 * 256;

inline constexpr uint8_t button_impulse = 1u << 0;

// The reason `input` cannot enter the world, or nothing when it can.
std::optional<std::string> check_input(const player_input& input);

// `input` with thrust and turn clamped to [−1, 1]. Call after check_input.
player_input clamp_input(const player_input& input);

// One tick's inputs: at most one per body. The world applies them in body id order,
// whatever order they are listed in.
struct body_input {
    world::body_id body_id;
    player_input input{};
};
using tick_inputs = std::vector<body_input>;

}  // namespace arena::world
