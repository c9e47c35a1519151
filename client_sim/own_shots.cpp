#include "client_sim/own_shots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "protocol/decode.hpp"
#include "server/world/broadphase.hpp"

namespace arena::bots {

namespace {

bool same_bits(const world::vec2& a, float x, float y) {
    const float predicted[2] = {a.x(), a.y()};
    const float server[2] = {x, y};
    return std::memcmp(predicted, server, sizeof predicted) == 0;
}

}  // namespace

own_shots::own_shots(const world::world_config& config, std::uint32_t player_id)
    : enabled_(config.rules == "asteroids"), player_id_(player_id) {
    // The server's parameters, from the Welcome's world config: it refused any it could not read.
    const auto params = rules::parse_asteroids_params(config.rules_params);
    if (params) {
        params_ = params.value;
    } else {
        enabled_ = false;  // nothing to predict by: the server's shots are shown as they come
    }
}

std::optional<predicted_shot> own_shots::fire(gun& g, std::uint32_t sequence, const world::player_input& input,
                                              world::body& ship) const {
    if (!enabled_ || (input.buttons & rules::button_fire) == 0) return std::nullopt;
    // The server removes a bullet fired in tick T after the step into T + lifetime: the input
    // of that tick no longer counts it.
    std::erase_if(g.live, [&](std::uint32_t fired) { return sequence - fired >= params_.bullet_lifetime_ticks; });
    if (!rules::may_fire(sequence, g.next_fire, static_cast<std::uint32_t>(g.live.size()), params_))
        return std::nullopt;
    const rules::shot s = rules::make_shot(ship, player_id_, params_);
    ship.apply_impulse(s.recoil);
    g.next_fire = sequence + params_.fire_cooldown_ticks;
    g.live.push_back(sequence);
    return predicted_shot{sequence, s.bullet.position, s.bullet.velocity};
}

void own_shots::forget_after(std::uint32_t sequence) {
    std::erase_if(waiting_, [sequence](const predicted_shot& p) { return p.sequence > sequence; });
}

own_shots::gun own_shots::on_snapshot(std::uint32_t tick, std::uint32_t ack,
                                      std::span<const protocol::ShotOrigin> origins,
                                      std::span<const protocol::BodyState> view, const world::world_config& config,
                                      std::vector<float>& errors) {
    gun g;
    if (!enabled_) return g;
    // Input `ack` was the last the world took, by `tick`; the inputs after it go one a tick.
    const std::int64_t tick_of_ack = static_cast<std::int64_t>(tick) - static_cast<std::int64_t>(ack);
    const auto tick_of = [&](std::uint32_t sequence) {
        return tick_of_ack + sequence;
    };
    const auto sequence_at = [&](std::int64_t t) {
        return static_cast<std::uint32_t>(std::clamp<std::int64_t>(t - tick_of_ack, 0, UINT32_MAX));
    };
    for (const protocol::ShotOrigin& o : origins) {
        if (o.owner() != player_id_) continue;
        const auto predicted = std::find_if(waiting_.begin(), waiting_.end(),
                                            [&](const predicted_shot& p) { return p.sequence == o.input_sequence(); });
        if (predicted == waiting_.end()) {
            // Described again (it came back into view, or an acknowledgement is on its way).
            if (last_confirmed_ && o.input_sequence() <= *last_confirmed_) continue;
            ++counts_.unpredicted;
        } else if (same_bits(predicted->position, o.x(), o.y()) && same_bits(predicted->velocity, o.vx(), o.vy())) {
            ++counts_.exact;
            waiting_.erase(predicted);
        } else {
            // Wrap-aware: a spawn across the edge from the prediction is near it, not a world away.
            const world::vec2 d = world::displacement(predicted->position, {o.x(), o.y()}, config);
            errors.push_back(std::sqrt(d.squaredNorm()));
            ++counts_.with_error;
            waiting_.erase(predicted);
        }
        // Fired when the world took its input: a tick estimated from this snapshot, exact
        // unless an input came late between that tick and this snapshot's.
        confirmed_.push_back({o.body_id(), o.input_sequence(), tick_of(o.input_sequence())});
        if (!last_confirmed_ || o.input_sequence() > *last_confirmed_) {
            last_confirmed_ = o.input_sequence();
            last_confirmed_tick_ = confirmed_.back().tick;
        }
    }
    counts_.unconfirmed += static_cast<std::uint64_t>(
        std::erase_if(waiting_, [ack](const predicted_shot& p) { return p.sequence <= ack; }));
    // A confirmed bullet no longer in view is gone: it hit something, or its lifetime ended.
    std::erase_if(confirmed_, [&](const confirmed_shot& c) { return protocol::find_body(view, c.body_id) == nullptr; });
    if (last_confirmed_) g.next_fire = sequence_at(last_confirmed_tick_ + params_.fire_cooldown_ticks);
    for (const confirmed_shot& c : confirmed_) g.live.push_back(sequence_at(c.tick));
    return g;
}

}  // namespace arena::bots
