#pragma once
// Asteroids' parameters, and how a world config's "rules_params" sets them: every field
// optional, the defaults below for the rest, anything else refused with the field's name. The
// server's rules and a client predicting its own shots read the same text (the Welcome's world
// config), so both play by the same numbers.
#include <cstdint>
#include <string_view>

#include "server/world/body.hpp"
#include "server/world/result.hpp"

namespace arena::rules {

struct asteroids_params {
    world::real bullet_impulse = 2.0f;    // N·s, J
    world::real bullet_mass = 0.05f;      // kg: 40 m/s from J = 2 N·s
    world::real bullet_radius = 0.2f;     // m
    uint32_t fire_cooldown_ticks = 6;     // 0.1 s at 60 Hz
    uint32_t bullet_lifetime_ticks = 72;  // 1.2 s at 60 Hz
    uint32_t max_bullets_per_ship = 4;    // live at once
    uint32_t lives = 3;                   // respawns: the fourth death is the last
    uint32_t respawn_ticks = 120;         // 2 s at 60 Hz
    uint32_t invulnerable_ticks = 120;    // 2 s after a respawn
    world::real split_impulse = 20.0f;    // N·s given to each piece, across the rock's velocity
    world::real wave_rock_radius = 5.0f;  // m, a new wave's large rocks
    world::real spawn_clearance = 15.0f;  // m kept free around a respawn or a wave's rock
    uint32_t score_large = 20, score_medium = 50, score_small = 100, score_ship = 200;
};

// The parameters a world config's rules_params text gives ("" or "{}": the defaults), or why
// not: "rules_params.FIELD: ..." for a field of the wrong type, out of its range, or unknown.
result<asteroids_params> parse_asteroids_params(std::string_view rules_params);

}  // namespace arena::rules
