#include "server/match/snapshot_fanout.hpp"

#include <algorithm>
#include <numeric>

#include "server/match/body_state.hpp"
#include "server/match/shape_wire.hpp"

namespace arena::match {

namespace delta = protocol::delta;

snapshot_fanout::snapshot_fanout(const fanout_config& config)
    // The shared state is kept for every tick (clients are spread over the interval), as far
    // back as a client's oldest kept snapshot.
    : config_(config), history_(tick_ring{config.ring.depth * config.ring.interval, 1}) {}

void snapshot_fanout::begin(const world::world& w, const body_kinds* kinds, const protocol::game_list* shared_game,
                            const shot_origins* origins) {
    world_ = &w;
    kinds_ = kinds != nullptr ? kinds : &no_kinds_;
    origins_ = origins;
    shared_game_ = shared_game;
    tick_ = w.tick();
    now_ = nullptr;
    states_ready_ = index_ready_ = shared_ready_ = false;
}

const std::vector<delta::quantized_body>& snapshot_fanout::quantized() {
    if (now_ == nullptr) now_ = &history_.record(tick_, world_->bodies());
    return *now_;
}

const std::vector<protocol::BodyState>& snapshot_fanout::states() {
    if (!states_ready_) {
        states_.clear();
        for (const world::body& b : world_->bodies()) states_.push_back(body_state(b));
        states_ready_ = true;
    }
    return states_;
}

void snapshot_fanout::build_shared() {
    if (!shared_ready_) {
        // Ids are never reused and grow: the bodies new since the last shared frame are those
        // from its next id on. Bodies whose kind changed since are described again.
        shared_shapes_.clear();
        const auto bodies = world_->bodies();
        retagged_.clear();
        kinds_->changed_after(shared_kinds_revision_, [&](uint32_t id) { retagged_.push_back(id); });
        shared_kinds_revision_ = kinds_->revision();
        size_t r = 0;
        for (const world::body& b : bodies) {
            while (r < retagged_.size() && retagged_[r] < b.id) ++r;
            const bool retagged = r < retagged_.size() && retagged_[r] == b.id;
            if (b.id >= shared_next_id_ || retagged) describe_body(shared_shapes_, b);
        }
        shared_.build(tick_, states(), &shared_shapes_, shared_game_);
        shared_base_tick_ = last_shared_tick_;
        last_shared_tick_ = tick_;
        if (!bodies.empty()) shared_next_id_ = std::max(shared_next_id_, bodies.back().id + 1);
        shared_ready_ = true;
    }
}

const protocol::snapshot_encoder* snapshot_fanout::shared_frame(snapshot_client& client) {
    build_shared();
    if (client.shared_tick == 0 || client.shared_tick != shared_base_tick_) return nullptr;
    client.shared_tick = tick_;
    ++counters_.full_frames;
    count_shapes(shared_shapes_);
    return &shared_;
}

void snapshot_fanout::describe_view(snapshot_client& client, uint32_t acked, bool reliable) {
    shapes_.clear();
    const auto bodies = world_->bodies();
    client.shapes.update(tick_, bodies, view_, acked, reliable, *kinds_,
                         [&](uint32_t i) { describe_body(shapes_, bodies[i]); });
    count_shapes(shapes_);
}

void snapshot_fanout::describe_body(protocol::shape_list& list, const world::body& b) const {
    list.append(describe(*world_, b, kinds_->of(b.id)));
    if (origins_ == nullptr) return;
    if (const protocol::ShotOrigin* origin = origins_->of(b.id)) list.origins.push_back(*origin);
}

void snapshot_fanout::count_shapes(const protocol::shape_list& list) {
    counters_.shapes_sent += list.shapes.size();
    counters_.shape_bytes += list.wire_bytes();
}

void snapshot_fanout::find_view(world::body_id own_id) {
    const uint32_t body_id = own_id.value();
    view_.clear();
    const auto bodies = world_->bodies();
    if (config_.view_radius <= 0 || !own_id) {
        view_.resize(bodies.size());
        std::iota(view_.begin(), view_.end(), 0u);
        return;
    }
    const auto own = std::lower_bound(bodies.begin(), bodies.end(), body_id,
                                      [](const world::body& b, uint32_t id) { return b.id < id; });
    if (own == bodies.end() || own->id != body_id) return;  // not spawned: an empty view
    // The own body is always within the radius of itself, so the query includes it.
    if (!index_ready_) {
        index_.build(bodies, world_->config(), config_.view_radius);
        index_ready_ = true;
    }
    index_.query(own->position, view_);
}

delta::shared_encoder& snapshot_fanout::encoder_for(uint32_t baseline_tick) {
    prepared_encoder* slot = nullptr;
    for (prepared_encoder& e : encoders_) {
        if (e.tick == tick_ && e.baseline_tick == baseline_tick) return e.encoder;
        if (e.tick != tick_ && slot == nullptr) slot = &e;  // stale: reusable
    }
    if (slot == nullptr) slot = &encoders_.emplace_back();
    slot->tick = tick_;
    slot->baseline_tick = baseline_tick;
    std::optional<delta::view> baseline;
    if (baseline_tick != 0) baseline = delta::view(*history_.at(baseline_tick));
    slot->encoder.prepare(quantized(), baseline, {tick_ - baseline_tick, config_.tick_rate});
    return slot->encoder;
}

std::span<const uint8_t> snapshot_fanout::delta_frame(snapshot_client& client, world::body_id own,
                                                      uint32_t ack_sequence, const protocol::game_list* game) {
    find_view(own);
    // This tick's state first: recording it replaces the ring's oldest tick, which must not
    // be picked as a baseline below (and then overwritten under the encoder's feet).
    quantized();
    // The baseline: the acknowledged view, when both its state and the client's record of it
    // are still kept (an ack of a tick never sent, or too old, finds nothing: a full view).
    uint32_t baseline_tick = 0;
    const std::vector<uint32_t>* held = nullptr;
    const uint32_t acked = client.acked_tick;
    if (acked != 0 && acked < tick_ && history_.at(acked) != nullptr) {
        held = client.views.at(acked);
        if (held != nullptr) baseline_tick = acked;
    }
    // Shapes are confirmed by any acknowledged snapshot this client was sent, a baseline or not.
    const uint32_t sent_ack = acked != 0 && acked < tick_ && client.views.at(acked) != nullptr ? acked : 0;
    if (client.budget != 0) return budgeted_frame(client, own, ack_sequence, baseline_tick, held, sent_ack, game);
    encoder_for(baseline_tick)
        .encode(view_, held != nullptr ? std::span<const uint32_t>(*held) : std::span<const uint32_t>(), delta_bytes_);
    describe_view(client, sent_ack, false);
    client.views.record(tick_, view_);

    const auto frame = protocol::encode_delta_snapshot(fbb_, tick_, ack_sequence, baseline_tick, delta_bytes_, &shapes_,
                                                       game, client.extra_inputs_waiting);
    ++(baseline_tick != 0 ? counters_.delta_frames : counters_.keyframes);
    counters_.delta_bytes += frame.size();
    counters_.delta_payload_bytes += delta_bytes_.size();
    counters_.delta_bodies += view_.size();
    return frame;
}

std::span<const uint8_t> snapshot_fanout::full_frame(snapshot_client& client, world::body_id own, uint32_t ack_sequence,
                                                     const protocol::game_list* game) {
    find_view(own);
    full_states_.clear();
    const auto& all = states();
    for (uint32_t i : view_) full_states_.push_back(all[i]);
    ++counters_.full_frames;
    // A stream delivers every frame: what this one describes, the client holds.
    describe_view(client, 0, true);
    if (shared_full_frame()) {
        // This tick's shared frame marks what the next one describes as new; this client now
        // holds everything up to it.
        build_shared();
        client.shared_tick = tick_;
    }
    return protocol::encode_snapshot(fbb_, tick_, ack_sequence, full_states_, &shapes_, game);
}

}  // namespace arena::match
