#include "server/net/snapshot_fanout.hpp"

#include <algorithm>
#include <numeric>

namespace arena::net {

namespace delta = protocol::delta;

snapshot_fanout::snapshot_fanout(const fanout_config& config) : config_(config), history_(config.ring) {}

void snapshot_fanout::begin(const world::world& w) {
    world_ = &w;
    tick_ = w.tick();
    now_ = &history_.record(tick_, w.bodies());
    states_.clear();
    for (const world::body& b : w.bodies()) {
        states_.emplace_back(b.id, b.owner, b.position.x(), b.position.y(), b.velocity.x(), b.velocity.y(), b.angle,
                             b.angular_velocity);
    }
    if (shared_full_frame()) {
        shared_.build(tick_, states_);
    } else {
        index_.build(w.bodies(), w.config(), config_.view_radius);
    }
}

void snapshot_fanout::find_view(uint32_t body_id) {
    view_.clear();
    const auto bodies = world_->bodies();
    if (config_.view_radius <= 0) {
        view_.resize(bodies.size());
        std::iota(view_.begin(), view_.end(), 0u);
        return;
    }
    const auto own = std::lower_bound(bodies.begin(), bodies.end(), body_id,
                                      [](const world::body& b, uint32_t id) { return b.id < id; });
    if (own == bodies.end() || own->id != body_id) return;  // not spawned: an empty view
    // The own body is always within the radius of itself, so the query includes it.
    index_.query(bodies, own->position, view_);
}

std::span<const uint8_t> snapshot_fanout::delta_frame(snapshot_client& client, uint32_t body_id,
                                                      uint32_t ack_sequence) {
    find_view(body_id);
    current_.clear();
    for (uint32_t i : view_) current_.push_back((*now_)[i]);

    // The baseline: the acknowledged view, when both its state and the client's record of it
    // are still kept (an ack of a tick never sent, or too old, finds nothing: a keyframe).
    std::optional<delta::view> baseline;
    uint32_t baseline_tick = 0;
    const uint32_t acked = client.acked_tick;
    if (acked != 0 && acked < tick_) {
        const auto* state = history_.at(acked);
        const auto* indices = client.views.at(acked);
        if (state != nullptr && indices != nullptr) {
            baseline_.clear();
            for (uint32_t i : *indices) baseline_.push_back((*state)[i]);
            baseline = delta::view(baseline_);
            baseline_tick = acked;
        }
    }
    delta::encode(current_, baseline, {tick_ - baseline_tick, config_.tick_rate}, delta_bytes_);
    client.views.record(tick_, view_);

    const auto frame = protocol::encode_delta_snapshot(fbb_, tick_, ack_sequence, baseline_tick, delta_bytes_);
    ++(baseline ? counters_.delta_frames : counters_.keyframes);
    counters_.delta_bytes += frame.size();
    counters_.delta_payload_bytes += delta_bytes_.size();
    counters_.delta_bodies += current_.size();
    return frame;
}

std::span<const uint8_t> snapshot_fanout::full_frame(uint32_t body_id, uint32_t ack_sequence) {
    find_view(body_id);
    full_states_.clear();
    for (uint32_t i : view_) full_states_.push_back(states_[i]);
    ++counters_.full_frames;
    return protocol::encode_snapshot(fbb_, tick_, ack_sequence, full_states_);
}

}  // namespace arena::net
