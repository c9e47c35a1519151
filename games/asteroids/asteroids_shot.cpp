#include "games/asteroids/asteroids_shot.hpp"

#include "server/world/trig.hpp"

namespace arena::rules {

bool may_fire(uint32_t now, uint32_t next_fire, uint32_t live, const asteroids_params& p) {
    return now >= next_fire && live < p.max_bullets_per_ship;
}

shot make_shot(const world::body& ship, uint32_t player_id, const asteroids_params& p) {
    const world::cos_sin r = world::compute_cos_sin(ship.angle);
    const world::vec2 facing{r.c, r.s};
    world::body_material m;
    m.mass = p.bullet_mass;
    m.radius = p.bullet_radius;
    m.restitution = 0;
    m.friction = 0;
    m.drag_area = 0;
    const world::real nose = ship.radius + p.bullet_radius + 0.1f;
    shot s{world::make_body(m, ship.position + facing * nose), {0, 0}};
    s.bullet.owner = 0;  // nobody steers it
    // The lecture's impulse both ways: Δv = J/m_bullet forwards, −J/m_ship back.
    const world::vec2 impulse = facing * p.bullet_impulse;
    s.bullet.velocity = ship.velocity;
    s.bullet.apply_impulse(impulse);
    // Its shooter's negative group: it passes through the ship that fired it.
    s.bullet.filter = {category_bullet, category_rock | category_ship, -static_cast<int32_t>(player_id)};
    s.recoil = -impulse;
    return s;
}

}  // namespace arena::rules
