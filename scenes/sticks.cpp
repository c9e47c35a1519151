#include "scenes/sticks.hpp"

#include <algorithm>

namespace arena::scenes {

bool move_stick_now_and_then(world::rng& r, world::player_input& stick) {
    if (r.next_u64() % 20 != 0) return false;
    // One draw per statement: argument evaluation order differs between compilers.
    const world::real thrust = r.uniform(-1, 1);
    const world::real turn = r.uniform(-1, 1);
    stick.thrust = thrust;
    stick.turn = turn;
    return true;
}

world::player_input wandering_stick::next(world::rng& r) {
    const float dthrust = r.uniform(-0.1f, 0.1f);
    const float dturn = r.uniform(-0.2f, 0.2f);
    thrust_ = std::clamp(thrust_ + dthrust, -0.2f, 1.0f);
    turn_ = std::clamp(turn_ + dturn, -1.0f, 1.0f);
    const bool impulse = r.next_u64() % 90 == 0;
    return {thrust_, turn_, impulse ? world::button_impulse : std::uint8_t{0}};
}

}  // namespace arena::scenes
