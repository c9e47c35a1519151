#include "server/world/input.hpp"

#include <algorithm>
#include <cmath>

namespace arena::world {

std::optional<std::string> check_input(const player_input& input) {
    if (!std::isfinite(input.thrust)) return "thrust is not a finite number";
    if (!std::isfinite(input.turn)) return "turn is not a finite number";
    return std::nullopt;
}

player_input clamp_input(const player_input& input) {
    return {std::clamp(input.thrust, -1.0f, 1.0f), std::clamp(input.turn, -1.0f, 1.0f), input.buttons};
}

}  // namespace arena::world
