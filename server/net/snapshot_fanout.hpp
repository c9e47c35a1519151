#pragma once
// Each client's snapshot frame for one tick (issue 7, protocol/README.md "Delta snapshots"):
// - clients that said Hello.delta_snapshots get their view, quantised, encoded against the
//   newest view they acknowledged that the server still keeps, else in full;
// - other clients get BodyState snapshots: one frame shared by all when the view is the whole
//   world, else one per client holding its view.
// A client's view is its own body and every body within view_radius of it, found through a
// grid index built once per snapshot (server/world/view_index.hpp).
#include <cstdint>
#include <span>
#include <vector>

#include "protocol/delta/codec.hpp"
#include "protocol/snapshot.hpp"
#include "server/net/view_history.hpp"
#include "server/world/view_index.hpp"
#include "server/world/world.hpp"

namespace arena::net {

struct fanout_config {
    float view_radius = 0;  // m; 0: the whole world
    tick_ring ring;         // how many snapshots are kept as baselines, and their interval
    uint16_t tick_rate = 60;
};

// What the fan-out keeps per client.
struct snapshot_client {
    explicit snapshot_client(tick_ring ring, bool delta) : delta(delta), views(ring) {}
    bool delta = false;        // the client decodes delta snapshots
    uint32_t acked_tick = 0;   // its newest Input.snapshot_ack; 0: none
    client_views views;        // what its recent snapshots held
};

struct fanout_counters {
    uint64_t delta_frames = 0;     // delta-encoded frames sent against a baseline
    uint64_t keyframes = 0;        // delta-encoded frames sent without one (new or lost client)
    uint64_t delta_bytes = 0;      // bytes of both kinds of frames
    uint64_t delta_payload_bytes = 0;  // the codec's bytes inside them (no FlatBuffers framing)
    uint64_t delta_bodies = 0;     // bodies in the views those frames carried
    uint64_t full_frames = 0;      // BodyState frames sent (clients without delta_snapshots)
};

class snapshot_fanout {
public:
    explicit snapshot_fanout(const fanout_config& config);

    // The tick's state: quantises it as this snapshot's baseline, indexes it for view queries,
    // and builds the shared BodyState frame when every client sees the whole world.
    void begin(const world::world& w);

    // The frame for a delta client whose body is `body_id`. Valid until the next call.
    std::span<const uint8_t> delta_frame(snapshot_client& client, uint32_t body_id, uint32_t ack_sequence);

    // True: BodyState clients share shared_frame(); false: each gets full_frame().
    [[nodiscard]] bool shared_full_frame() const { return config_.view_radius <= 0; }
    // The shared frame; counts one client served.
    [[nodiscard]] const protocol::snapshot_encoder& shared_frame() {
        ++counters_.full_frames;
        return shared_;
    }
    [[nodiscard]] size_t shared_frame_bytes() const { return shared_.frame().size(); }
    // The BodyState frame of one client's view. Valid until the next call.
    std::span<const uint8_t> full_frame(uint32_t body_id, uint32_t ack_sequence);

    [[nodiscard]] const fanout_counters& counters() const { return counters_; }
    [[nodiscard]] const fanout_config& config() const { return config_; }

private:
    // Indices (into the world's body span) of what the body `body_id` sees, into view_.
    void find_view(uint32_t body_id);

    fanout_config config_;
    const world::world* world_ = nullptr;
    uint32_t tick_ = 0;
    quantized_history history_;
    const std::vector<protocol::delta::quantized_body>* now_ = nullptr;  // this tick's in history_
    world::view_index index_;
    protocol::snapshot_encoder shared_;
    std::vector<protocol::BodyState> states_;  // this tick's bodies as BodyState
    std::vector<uint32_t> view_;
    std::vector<protocol::delta::quantized_body> current_, baseline_;
    std::vector<uint8_t> delta_bytes_;
    std::vector<protocol::BodyState> full_states_;
    flatbuffers::FlatBufferBuilder fbb_{1024};
    fanout_counters counters_;
};

}  // namespace arena::net
