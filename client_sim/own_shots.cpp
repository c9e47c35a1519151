#include "client_sim/own_shots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "games/registry.hpp"
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

own_shots::own_shots(const world::world_config& config, std::uint32_t player_id) : player_id_(player_id) {
    // The server's parameters, from the Welcome's world config. A game this build does not
    // know, or parameters it cannot read: nothing to predict by, the server's shots are shown
    // as they come.
    const rules::game_definition* game = games::find(config.rules);
    if (game != nullptr && game->make_shot_rule != nullptr) rule_ = game->make_shot_rule(config.rules_params);
}

std::optional<predicted_shot> own_shots::fire(gun& g, std::uint32_t sequence, const world::player_input& input,
                                              world::body& ship) const {
    if (!rule_ || (input.buttons & rule_->fire_buttons()) == 0) return std::nullopt;
    // The server removes a bullet fired in tick T after the step into T + lifetime: the input
    // of that tick no longer counts it.
    const std::uint32_t lifetime = rule_->lifetime_ticks();
    std::erase_if(g.live, [&](std::uint32_t fired) { return sequence - fired >= lifetime; });
    if (!rule_->may_fire(sequence, g.next_fire, static_cast<std::uint32_t>(g.live.size()))) return std::nullopt;
    const rules::fired_shot s = rule_->fire(ship, player_id_);
    ship.apply_impulse(s.recoil);
    g.next_fire = sequence + rule_->cooldown_ticks();
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
    if (!rule_) return g;
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
    if (last_confirmed_) g.next_fire = sequence_at(last_confirmed_tick_ + rule_->cooldown_ticks());
    for (const confirmed_shot& c : confirmed_) g.live.push_back(sequence_at(c.tick));
    return g;
}

}  // namespace arena::bots
