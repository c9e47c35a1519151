#pragma once
// What the server remembers of the snapshots it sent, so that it can encode each client's
// next snapshot against the one the client acknowledged (delta snapshots, protocol/README.md):
// - the quantised world at each of the last `depth` snapshot ticks, shared by every client;
// - per client, which of those bodies each of its last `depth` snapshots held (indices into
//   the shared state: 4 bytes a body instead of 28), and the few it holds at other states.
// Both are rings keyed by tick, so a baseline is found in O(1) and memory stays bounded.
#include <cstdint>
#include <span>
#include <vector>

#include "protocol/delta/quantize.hpp"
#include "protocol/delta/shared_encoder.hpp"
#include "server/world/body.hpp"

namespace arena::match {

// The ring slot of a tick: snapshot ticks are multiples of one interval, so consecutive
// snapshots take consecutive slots.
struct tick_ring {
    uint32_t depth = 32;    // snapshots kept
    uint32_t interval = 1;  // ticks between snapshots
    [[nodiscard]] size_t slot(uint32_t tick) const { return (tick / interval) % depth; }
};

class quantized_history {
public:
    explicit quantized_history(tick_ring ring);
    // Quantises `bodies` (sorted by id) as snapshot `tick`'s state, replacing the oldest.
    const std::vector<protocol::delta::quantized_body>& record(uint32_t tick, std::span<const world::body> bodies);
    // Snapshot `tick`'s state, or null when it was never recorded or is no longer kept.
    [[nodiscard]] const std::vector<protocol::delta::quantized_body>* at(uint32_t tick) const;

private:
    struct entry {
        uint32_t tick = 0;  // 0: empty (snapshots follow a step, so their ticks are ≥ 1)
        std::vector<protocol::delta::quantized_body> bodies;
    };
    tick_ring ring_;
    std::vector<entry> entries_;
};

class client_views {
public:
    explicit client_views(tick_ring ring);
    using held_body = protocol::delta::shared_encoder::held_body;
    // The view sent at `tick`: indices into that tick's quantized_history state, increasing;
    // `held`: those of its bodies the client holds at other states (left out of a snapshot
    // under a bandwidth budget, kept as predicted), by increasing index.
    void record(uint32_t tick, std::span<const uint32_t> indices, std::span<const held_body> held = {});
    [[nodiscard]] const std::vector<uint32_t>* at(uint32_t tick) const;
    // The held bodies of the view at `tick` (empty when none, or not kept).
    [[nodiscard]] std::span<const held_body> held_at(uint32_t tick) const;
    // The game's version (game_feed.hpp) through which the snapshot of `tick`, recorded
    // before, completed the client's game lists; 0 when that snapshot is not kept.
    void record_game(uint32_t tick, uint32_t version);
    [[nodiscard]] uint32_t game_at(uint32_t tick) const;

private:
    struct entry {
        uint32_t tick = 0;
        std::vector<uint32_t> indices;
        std::vector<held_body> held;
        uint32_t game = 0;
    };
    tick_ring ring_;
    std::vector<entry> entries_;
};

}  // namespace arena::match
