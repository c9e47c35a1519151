#include "games/asteroids/asteroids_params.hpp"

#include "server/rules/params_reader.hpp"

namespace arena::rules {

result<asteroids_params> parse_asteroids_params(std::string_view rules_params) {
    return read_params(rules_params, asteroids_params{}, [](params_reader& r, asteroids_params& p) {
        // Bounds that keep a match playable and its memory bounded: a bullet can neither stand
        // still nor be massless, a ship has at most 64 live bullets, counts stay in 32 bits.
        r.number("bullet_impulse", p.bullet_impulse, 0, 1e4, true);
        r.number("bullet_mass", p.bullet_mass, 0, 1e3, true);
        r.number("bullet_radius", p.bullet_radius, 0, 10, true);
        r.whole("fire_cooldown_ticks", p.fire_cooldown_ticks, 0, 36'000);
        r.whole("bullet_lifetime_ticks", p.bullet_lifetime_ticks, 1, 36'000);
        r.whole("max_bullets_per_ship", p.max_bullets_per_ship, 0, 64);
        r.whole("lives", p.lives, 0, 1'000);
        r.whole("respawn_ticks", p.respawn_ticks, 1, 36'000);
        r.whole("invulnerable_ticks", p.invulnerable_ticks, 0, 36'000);
        r.number("split_impulse", p.split_impulse, 0, 1e5);
        r.number("wave_rock_radius", p.wave_rock_radius, 0, 100, true);
        r.number("spawn_clearance", p.spawn_clearance, 0, 1e4);
        r.whole("score_large", p.score_large, 0, 1'000'000);
        r.whole("score_medium", p.score_medium, 0, 1'000'000);
        r.whole("score_small", p.score_small, 0, 1'000'000);
        r.whole("score_ship", p.score_ship, 0, 1'000'000);
    });
}

}  // namespace arena::rules
