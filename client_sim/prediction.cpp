#include "client_sim/prediction.hpp"

#include <algorithm>
#include <cmath>

#include "server/world/assert.hpp"
#include "server/world/broadphase.hpp"

namespace arena::bots {

world::world_config predictor::local_config(const world::world_config& server_config) {
    world::world_config c = server_config;
    // The server's rocks are its own business: we see them only through snapshots and do not
    // simulate them (a lone body is what the prediction is exact for).
    c.rocks.count = 0;
    if (c.boundary == world::boundary::wrap) {
        // The wrap-around broadphase visits every grid cell each step, and cells are sized by
        // the largest body: for one 1.5 m ship in a 400 m world that is 17 000 cells and
        // 0.7 ms a step, 40 % of a core for 10 bots. Cells as large as the world make it test
        // pairs directly (none, for one body). In a wrapping world speculative_distance is used
        // only by the broadphase grid and by pair contacts (walls exist only with the walls
        // and floor boundaries), so for a lone body the results are bit-identical; the
        // zero-latency test compares against a world with the server's unmodified config.
        c.speculative_distance = std::max(c.size.x(), c.size.y());
    }
    return c;
}

predictor::predictor(const world::world_config& server_config, std::uint32_t entity_id, std::uint32_t player_id)
    : config_(local_config(server_config)),
      entity_id_(entity_id),
      player_id_(player_id),
      acked_(config_, 0),
      predicted_(config_, 0),
      inputs_{world::body_input{world::body_id{entity_id}, {}}},
      shots_(config_, player_id) {
    pending_.reserve(64);
}

const world::body* predictor::body() const {
    return placed_ ? predicted_.find(entity_id_) : nullptr;
}

void predictor::step(world::world& w, const world::player_input& input) {
    inputs_[0].input = input;
    w.step(inputs_);
}

void predictor::step_predicted(std::uint32_t sequence, const world::player_input& input) {
    // Before the step, as the server's rules fire in before_step.
    if (alive_) {
        if (const auto shot = shots_.fire(gun_, sequence, input, *predicted_.find(entity_id_))) shots_.predicted(*shot);
    }
    step(predicted_, input);
}

void predictor::on_input(std::uint32_t sequence, const world::player_input& input) {
    ARENA_ASSERT(sequence == last_sequence_ + 1, "inputs are numbered 1, 2, 3, ... without gaps");
    last_sequence_ = sequence;
    if (pending_.size() >= max_pending) {
        pending_.erase(pending_.begin());
        ++dropped_;
    }
    pending_input p{sequence, input, false, {0, 0}};
    if (placed_) {
        step_predicted(sequence, input);
        p.predicted = true;
        p.position = predicted_.find(entity_id_)->position;
    }
    pending_.push_back(p);
}

const predictor::pending_input* predictor::find(std::uint32_t sequence) const {
    if (pending_.empty() || sequence < pending_.front().sequence) return nullptr;
    const std::size_t i = sequence - pending_.front().sequence;
    // Sequences are consecutive (on_input asserts it; only the oldest are ever dropped).
    return i < pending_.size() ? &pending_[i] : nullptr;
}

void predictor::drop_through(std::uint32_t sequence) {
    auto end = std::find_if(pending_.begin(), pending_.end(),
                            [sequence](const pending_input& p) { return p.sequence > sequence; });
    pending_.erase(pending_.begin(), end);
}

void predictor::set_state(world::world& w, const protocol::BodyState& own) {
    world::body* b = w.find(entity_id_);
    // Only what a snapshot carries; impulse_cooldown stays as our own steps left it.
    b->position = {own.x(), own.y()};
    b->velocity = {own.vx(), own.vy()};
    b->angle = own.angle();
    b->angular_velocity = own.angular_velocity();
}

void predictor::place_body(const protocol::BodyState& own) {
    world::body b = world::make_body(config_.player, {own.x(), own.y()});
    b.id = entity_id_;
    b.owner = player_id_;
    acked_.add_body(b);
    set_state(acked_, own);
    placed_ = true;
}

predictor::correction predictor::on_snapshot(std::uint32_t tick, std::uint32_t ack_sequence,
                                             const protocol::BodyState* own, std::span<const protocol::BodyState> view,
                                             std::span<const protocol::ShotOrigin> origins) {
    correction c;
    if (ack_sequence < acked_sequence_) {
        c.problem = ack_problem::went_back;
        return c;
    }
    if (ack_sequence > last_sequence_) {
        c.problem = ack_problem::ahead;
        return c;
    }
    // The gun after ack_sequence, as the server's confirmed shots tell it.
    const own_shots::gun acked_gun = shots_.on_snapshot(tick, ack_sequence, origins, view, config_, shot_errors_);
    alive_ = own != nullptr;
    // Without our body there is nothing to reset to; keep every input for the next snapshot.
    if (own == nullptr) return c;
    c.own_found = true;

    if (const pending_input* p = find(ack_sequence); p != nullptr && p->predicted) {
        // Wrap-aware: a body that just crossed the edge is a few cm away, not a world away.
        const world::vec2 d = world::displacement(p->position, {own->x(), own->y()}, config_);
        c.error = std::sqrt(d.squaredNorm());
    }

    if (!placed_) {
        place_body(*own);
    } else {
        // Carry acked_ to ack_sequence with the inputs the server consumed since the last
        // snapshot, then take the server's state for what a snapshot carries.
        for (const pending_input& p : pending_) {
            if (p.sequence > ack_sequence) break;
            if (p.sequence > acked_sequence_) step(acked_, p.input);
        }
        set_state(acked_, *own);
    }
    drop_through(ack_sequence);
    acked_sequence_ = ack_sequence;

    // Copy-assignment reuses predicted_'s buffers: no allocation once warm.
    predicted_ = acked_;
    gun_ = acked_gun;
    shots_.forget_after(ack_sequence);
    for (const pending_input& p : pending_) step_predicted(p.sequence, p.input);
    c.replayed = static_cast<std::uint32_t>(pending_.size());
    return c;
}

}  // namespace arena::bots
