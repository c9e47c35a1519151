#pragma once
// Soccer's parameters, and how a world config's "rules_params" sets them (params_reader.hpp:
// every field optional, anything else refused with the field's name).
#include <cstdint>
#include <string_view>

#include "server/world/result.hpp"
#include "server/world/types.hpp"

namespace arena::rules {

struct soccer_params {
    uint32_t match_seconds = 180;       // the match clock; the match ends when it runs out
    uint32_t periods = 2;               // the clock's equal parts (halves); a kick-off starts each
    world::real kick_impulse = 5.0f;    // N·s, J: the ball's Δv = J/m (11 m/s for 0.45 kg)
    world::real kick_reach = 0.3f;      // m between the kicker's edge and the ball's
    uint32_t kick_cooldown_ticks = 12;  // 0.2 s at 60 Hz
    world::real ball_friction = 0.05f;  // μ of the ball rolling on the pitch: a = μ·g
    world::real gravity = 9.81f;        // m/s², g in N = m·g (the pitch is seen from above)
    uint32_t kickoff_ticks = 120;       // 2 s from a goal to the kick-off
};

// The parameters a world config's rules_params text gives ("" or "{}": the defaults), or why
// not: "rules_params.FIELD must be ..." for a field of the wrong type, out of its range, or unknown.
result<soccer_params> parse_soccer_params(std::string_view rules_params);

}  // namespace arena::rules
