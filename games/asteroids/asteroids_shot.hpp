#pragma once
// The Asteroids fire rule as pure functions of the ship's state, so that the server's rules
// (asteroids_rules.cpp) and a client predicting its own ship and bullets (client_sim/
// prediction.hpp) run the same code and, from the same state and input, get the same floats.
// Links only the world: the client core and its WebAssembly build use it too.
#include <cstdint>

#include <memory>
#include <string_view>

#include "games/asteroids/asteroids_params.hpp"
#include "server/rules/shot_rule.hpp"
#include "server/world/body.hpp"

namespace arena::rules {

inline constexpr uint8_t button_fire = 1u << 1;

// Filter categories (world/filter.hpp). Rocks keep the default category 1.
inline constexpr uint32_t category_rock = 1u << 0;
inline constexpr uint32_t category_ship = 1u << 1;
inline constexpr uint32_t category_bullet = 1u << 2;

// May a ship fire at tick `now`, its cooldown ending at tick `next_fire`, with `live` of its
// bullets in the world? The client asks with input sequences for ticks (one input a tick).
[[nodiscard]] bool may_fire(uint32_t now, uint32_t next_fire, uint32_t live, const asteroids_params& p);

// One shot from `ship`, owned by `player_id`: the bullet (no id yet) at the nose with the
// ship's velocity plus J/m_bullet along the facing, and the impulse −J the ship takes.
using shot = fired_shot;
[[nodiscard]] shot make_shot(const world::body& ship, uint32_t player_id, const asteroids_params& p);

// The same, as the shot rule a client predicting its own shots runs (shot_rule.hpp).
class asteroids_shot_rule final : public shot_rule {
public:
    explicit asteroids_shot_rule(const asteroids_params& p) : params_(p) {}
    uint8_t fire_buttons() const override { return button_fire; }
    uint32_t cooldown_ticks() const override { return params_.fire_cooldown_ticks; }
    uint32_t lifetime_ticks() const override { return params_.bullet_lifetime_ticks; }
    bool may_fire(uint32_t now, uint32_t next_fire, uint32_t live) const override {
        return rules::may_fire(now, next_fire, live, params_);
    }
    fired_shot fire(const world::body& ship, uint32_t player_id) const override {
        return make_shot(ship, player_id, params_);
    }
    const asteroids_params& params() const { return params_; }

private:
    asteroids_params params_;
};

}  // namespace arena::rules
