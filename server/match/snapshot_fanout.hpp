#pragma once
// Each client's snapshot frame for one tick (protocol/README.md "Delta snapshots"):
// - clients that said Hello.delta_snapshots get their view, quantised, encoded against the
//   newest view they acknowledged that the server still keeps, else in full;
// - other clients get BodyState snapshots: one frame shared by all when the view is the whole
//   world, else one per client holding its view.
// A client's view is its own body and every body within view_radius of it, found through a
// grid index built once per tick that sends snapshots (server/world/view_index.hpp). A client
// without a body (`own` none: a spectator) sees the whole world: it watches the match, not one
// ship's surroundings, and the scoreboard it reads covers every player.
// Every frame also describes the shapes of the view's bodies that its client may not hold
// yet (shape_tracker.hpp; protocol/README.md "Shapes"). The shared frame describes the
// bodies spawned since the previous shared frame, so it serves exactly the clients that got
// that one; any other BodyState client gets a frame of its own.
//
// A delta client with a byte budget (UDP: one datagram, snapshot_budget.cpp) gets a frame
// within it: when its view does not fit, a priority accumulator picks the bodies that go in,
// and the client keeps the others as predicted.
//
// Delta clients are spread over the ticks between two snapshots (match.cpp), so the fan-out
// runs every tick for a share of them: each piece of per-tick work (quantising, indexing, the
// shared frame) is done on first use in that tick.
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "protocol/delta/codec.hpp"
#include "protocol/delta/shared_encoder.hpp"
#include "protocol/snapshot.hpp"
#include "server/match/body_kinds.hpp"
#include "server/match/shape_tracker.hpp"
#include "server/match/shot_origins.hpp"
#include "server/match/snapshot_priority.hpp"
#include "server/match/view_history.hpp"
#include "server/world/view_index.hpp"
#include "server/world/world.hpp"

namespace arena::match {

struct fanout_config {
    float view_radius = 0;  // m; 0: the whole world
    tick_ring ring;         // a client's snapshots kept as baselines, and their interval
    uint16_t tick_rate = 60;
};

// What the fan-out keeps per client.
struct snapshot_client {
    explicit snapshot_client(tick_ring ring, bool delta, size_t budget = 0)
        : delta(delta), budget(budget), views(ring) {}
    bool delta = false;                 // the client decodes delta snapshots
    size_t budget = 0;                  // delta clients: bytes a snapshot frame may take; 0: no limit
    uint32_t acked_tick = 0;            // its newest Input.snapshot_ack; 0: none
    uint16_t extra_inputs_waiting = 0;  // its inputs waiting beyond the first, told in its next delta frame
    client_views views;                 // what its recent snapshots held
    shape_tracker shapes;               // which shapes it holds
    uint32_t shared_tick = 0;           // BodyState clients of a whole-world view: the tick of its last frame
    priority_accumulator priorities;    // with a budget: which bodies go in next

    // An Input's snapshot_ack (inputs come in order: the newest).
    void acknowledge(uint32_t tick) { acked_tick = tick; }

    // The game's version it holds (game_feed.hpp): the most its acknowledged snapshots brought.
    // A snapshot still kept adds what it brought; an older one changes nothing, so an ack that
    // comes back after a long loss does not make the client look as if it held nothing. Asked
    // when its next snapshot is built, not at every ack: reading its record then was a cache
    // miss per Input, and the newest ack brought the most (a later snapshot carries more).
    uint32_t game_held() {
        game_held_ = std::max(game_held_, views.game_at(acked_tick));
        return game_held_;
    }

private:
    uint32_t game_held_ = 0;
};

struct fanout_counters {
    uint64_t delta_frames = 0;         // delta-encoded frames sent against a baseline
    uint64_t keyframes = 0;            // delta-encoded frames sent without one (new or lost client)
    uint64_t delta_bytes = 0;          // bytes of both kinds of frames
    uint64_t delta_payload_bytes = 0;  // the codec's bytes inside them (no FlatBuffers framing)
    uint64_t delta_bodies = 0;         // bodies in the views those frames carried
    uint64_t full_frames = 0;          // BodyState frames sent (clients without delta_snapshots)
    uint64_t shapes_sent = 0;          // body shapes described, summed over the clients that got them
    uint64_t shape_bytes = 0;          // their BodyShape, ShapeVertex and ShotOrigin bytes, summed the same way
    uint64_t trimmed_frames = 0;       // delta frames that held part of their view (over the client's budget)
    uint64_t left_out_bodies = 0;      // bodies of their views those frames left out, summed
};

class snapshot_fanout {
public:
    explicit snapshot_fanout(const fanout_config& config);

    // A new tick of this world: what the previous tick prepared is stale. `kinds` tags the
    // bodies' shapes (null: every body is kind 0); it must outlive the tick. `shared_game`:
    // what the shared frame carries of the game (the lines and events after
    // last_shared_tick(), game_feed.hpp), likewise. `origins`: the bullets' origins, sent with
    // their shapes (null: none), likewise.
    void begin(const world::world& w, const body_kinds* kinds = nullptr,
               const protocol::game_list* shared_game = nullptr, const shot_origins* origins = nullptr);
    // The tick of the newest shared frame (0: none yet).
    [[nodiscard]] uint32_t last_shared_tick() const { return last_shared_tick_; }

    // The frame for a delta client whose body is `own`, carrying `game` (optional). Valid
    // until the next call.
    std::span<const uint8_t> delta_frame(snapshot_client& client, world::body_id own, uint32_t ack_sequence,
                                         const protocol::game_list* game = nullptr);

    // True: BodyState clients share shared_frame(); false: each gets full_frame().
    [[nodiscard]] bool shared_full_frame() const { return config_.view_radius <= 0; }
    // The shared frame, and counts one client served; null when this client did not get the
    // previous one (it then needs full_frame() to learn the shapes it lacks).
    [[nodiscard]] const protocol::snapshot_encoder* shared_frame(snapshot_client& client);
    // The BodyState frame of one client's view. Valid until the next call.
    std::span<const uint8_t> full_frame(snapshot_client& client, world::body_id own, uint32_t ack_sequence,
                                        const protocol::game_list* game = nullptr);

    [[nodiscard]] const fanout_counters& counters() const { return counters_; }
    [[nodiscard]] const fanout_config& config() const { return config_; }

private:
    // Indices (into the world's body span) of what the body `own` sees, into view_; every body
    // when `own` is none.
    void find_view(world::body_id own);
    // This tick's work, each done once on first use.
    const std::vector<protocol::delta::quantized_body>& quantized();
    const std::vector<protocol::BodyState>& states();
    // This tick's shared encoder against the state of `baseline_tick` (0: none), prepared on
    // first use: clients that acknowledged the same tick share its per-body work.
    protocol::delta::shared_encoder& encoder_for(uint32_t baseline_tick);
    // Into shapes_: the shapes of view_'s bodies that `client` lacks (acked: a tick sent to it).
    void describe_view(snapshot_client& client, uint32_t acked, bool reliable);
    void count_shapes(const protocol::shape_list& list);
    // Appends body b's shape to `list`, and its origin when it is a bullet.
    void describe_body(protocol::shape_list& list, const world::body& b) const;
    void build_shared();  // this tick's shared frame, once
    // delta_frame() for a client with a budget (snapshot_budget.cpp).
    std::span<const uint8_t> budgeted_frame(snapshot_client& client, world::body_id own, uint32_t ack_sequence,
                                            uint32_t baseline_tick, const std::vector<uint32_t>* held,
                                            uint32_t sent_ack, const protocol::game_list* game);

    fanout_config config_;
    const world::world* world_ = nullptr;
    uint32_t tick_ = 0;
    quantized_history history_;
    const std::vector<protocol::delta::quantized_body>* now_ = nullptr;  // this tick's in history_
    bool states_ready_ = false, index_ready_ = false, shared_ready_ = false;
    world::view_index index_;
    protocol::snapshot_encoder shared_;
    std::vector<protocol::BodyState> states_;  // this tick's bodies as BodyState
    std::vector<uint32_t> view_;
    struct prepared_encoder {
        uint32_t tick = 0;  // the tick it was prepared in; stale when not this one
        uint32_t baseline_tick = 0;
        protocol::delta::shared_encoder encoder;
    };
    std::vector<prepared_encoder> encoders_;  // a handful: one per baseline in use
    std::vector<uint8_t> delta_bytes_;
    std::vector<protocol::BodyState> full_states_;
    const body_kinds* kinds_ = nullptr;
    const shot_origins* origins_ = nullptr;
    const protocol::game_list* shared_game_ = nullptr;
    body_kinds no_kinds_;
    protocol::shape_list shapes_;         // this frame's descriptions
    protocol::shape_list shared_shapes_;  // the shared frame's
    uint32_t last_shared_tick_ = 0;       // the tick of the newest shared frame
    uint32_t shared_base_tick_ = 0;       // the shared frame's predecessor: its clients can use it
    uint32_t shared_next_id_ = 0;         // bodies from this id on are new since the last shared frame
    uint64_t shared_kinds_revision_ = 0;  // the kinds as the last shared frame described them
    std::vector<uint32_t> retagged_;      // bodies whose kind changed since, by id
    flatbuffers::FlatBufferBuilder fbb_{1024};
    // budgeted_frame()'s scratch
    std::vector<uint8_t> chosen_;
    std::vector<uint32_t> sent_;
    std::vector<client_views::held_body> held_;
    shape_tracker trial_shapes_;
    fanout_counters counters_;
};

}  // namespace arena::match
