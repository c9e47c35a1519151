#pragma once
// A game's fire rule as a client runs it to predict its own shots (client_sim/own_shots.hpp):
// the same code the game's rules fire with on the server, so that from the same state and
// input the client's bullet and recoil are the server's to the bit. A game whose players fire
// shots the clients should predict returns one from its definition's make_shot_rule
// (server/rules/game.hpp); the server's rules report each shot's origin (rules::shot_of) for
// the client to match its prediction with.
#include <cstdint>

#include "server/world/body.hpp"

namespace arena::rules {

// One shot: the bullet's spawn (no id yet) and the impulse its shooter takes.
struct fired_shot {
    world::body bullet;
    world::vec2 recoil{0, 0};  // N·s, for shooter.apply_impulse
};

class shot_rule {
public:
    virtual ~shot_rule() = default;
    // The Input.buttons bits that fire.
    [[nodiscard]] virtual uint8_t fire_buttons() const = 0;
    // Ticks between two shots of one shooter, and a bullet's life: the server removes a bullet
    // fired in tick T after the step into T + lifetime.
    [[nodiscard]] virtual uint32_t cooldown_ticks() const = 0;
    [[nodiscard]] virtual uint32_t lifetime_ticks() const = 0;
    // May a shooter fire at tick `now`, its cooldown ending at `next_fire`, with `live` of its
    // bullets in the world? (A client asks in input sequences: one input a tick.)
    [[nodiscard]] virtual bool may_fire(uint32_t now, uint32_t next_fire, uint32_t live) const = 0;
    // The shot `shooter`, owned by player `player_id`, fires now.
    [[nodiscard]] virtual fired_shot fire(const world::body& shooter, uint32_t player_id) const = 0;
};

}  // namespace arena::rules
