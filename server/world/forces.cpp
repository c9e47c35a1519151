#include "server/world/forces.hpp"

#include "server/world/trig.hpp"

namespace arena::world {

void apply_player_input(body& b, const player_input& input, const control_config& control, bool on_ground) {
    const cos_sin facing = compute_cos_sin(b.angle);
    const vec2 thrust_dir = control.thrust_along_facing ? vec2{facing.c, facing.s} : vec2{1, 0};
    b.apply_force(thrust_dir * (input.thrust * control.thrust_force));
    b.apply_torque(input.turn * control.turn_torque);
    const bool wants_impulse = (input.buttons & button_impulse) != 0;
    const bool allowed = b.impulse_cooldown == 0 && (!control.impulse_needs_ground || on_ground);
    if (wants_impulse && allowed) {
        const vec2 impulse_dir = control.impulse_upward ? vec2{0, 1} : vec2{facing.c, facing.s};
        b.apply_impulse(impulse_dir * control.impulse);
        b.impulse_cooldown = control.impulse_cooldown_ticks;
    }
}

}  // namespace arena::world
