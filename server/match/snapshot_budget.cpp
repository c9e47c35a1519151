// snapshot_fanout::budgeted_frame(): a delta client's frame within its byte budget. The whole
// view goes when it fits; otherwise the longest prefix of the priority ranking (the own body
// first) that fits, found by bisection over real encodings, so the bound holds exactly
// (header, shapes and FlatBuffers framing included). The bodies of the client's baseline
// left out are kept by the client as predicted; client_views remembers what it then holds,
// and the next frame is encoded against that.
#include "server/match/shape_wire.hpp"
#include "server/match/snapshot_fanout.hpp"

namespace arena::match {

std::span<const uint8_t> snapshot_fanout::budgeted_frame(snapshot_client& client, world::body_id own,
                                                         uint32_t ack_sequence, uint32_t baseline_tick,
                                                         const std::vector<uint32_t>* held, uint32_t sent_ack,
                                                         const protocol::game_list* game) {
    const auto bodies = world_->bodies();
    protocol::delta::shared_encoder& encoder = encoder_for(baseline_tick);
    const std::span<const uint32_t> base_view =
        held != nullptr ? std::span<const uint32_t>(*held) : std::span<const uint32_t>();
    const std::span<const client_views::held_body> base_held =
        baseline_tick != 0 ? client.views.held_at(baseline_tick) : std::span<const client_views::held_body>();
    client.priorities.accumulate(bodies, view_, own.value(), *kinds_, world_->config());
    const std::span<const uint32_t> ranked = client.priorities.ranked();

    // The frame holding the first n ranked bodies, its shapes tracked in trial_shapes_.
    // Everything the frame carries must be encoded here, so that the size tested is the size
    // sent (anything added to the frame later would break the bound).
    std::span<const uint8_t> frame;
    size_t built = 0;
    auto build = [&](size_t n) {
        chosen_.assign(view_.size(), 0);
        for (size_t k = 0; k < n; ++k) chosen_[ranked[k]] = 1;
        encoder.encode_chosen(view_, chosen_, base_view, base_held, sent_, held_, delta_bytes_);
        trial_shapes_ = client.shapes;
        shapes_.clear();
        trial_shapes_.update(tick_, bodies, sent_, sent_ack, false, *kinds_,
                             [&](uint32_t i) { describe_body(shapes_, bodies[i]); });
        frame = protocol::encode_delta_snapshot(fbb_, tick_, ack_sequence, baseline_tick, delta_bytes_, &shapes_, game,
                                                client.extra_inputs_waiting);
        built = n;
        return frame.size() <= client.budget;
    };
    size_t n = view_.size();
    if (!build(n)) {
        // The own body always goes (ranked first), even when it alone does not fit.
        size_t fits = std::min<size_t>(1, n), over = n;
        while (over - fits > 1) {
            const size_t mid = fits + (over - fits) / 2;
            (build(mid) ? fits : over) = mid;
        }
        n = fits;
        if (built != n) build(n);
        ++counters_.trimmed_frames;
        counters_.left_out_bodies += view_.size() - n;
    }
    client.shapes = trial_shapes_;
    count_shapes(shapes_);
    client.views.record(tick_, sent_, held_);
    client.priorities.sent(chosen_);

    ++(baseline_tick != 0 ? counters_.delta_frames : counters_.keyframes);
    counters_.delta_bytes += frame.size();
    counters_.delta_payload_bytes += delta_bytes_.size();
    counters_.delta_bodies += n;
    return frame;
}

}  // namespace arena::match
