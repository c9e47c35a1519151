#pragma once
// Which bodies of a client's view go into a snapshot that cannot hold them all (a bandwidth
// budget per client: over UDP one snapshot is one datagram, never fragmented). Glenn
// Fiedler's priority accumulator ("State Synchronization"): every snapshot, each body of the
// view adds its priority for this snapshot (by its kind's weight, which the game's rules give,
// and by distance from the client's own body) to what it accumulated; the highest go in and start again from 0, so a
// body left out climbs until it goes in. Priorities are integers and ties go to the lower id: the choice is a pure
// function of the views, the same on every run.
//
// Gains stay within a factor of 16 of each other (weight 1..4 × distance 1..4), so a far rock
// waits at most ~16 times as long as a near ship, never forever.
#include <cstdint>
#include <span>
#include <vector>

#include "server/match/body_kinds.hpp"
#include "server/world/body.hpp"
#include "server/world/config.hpp"

namespace arena::match {

class priority_accumulator {
public:
    // This snapshot's view of `own` (increasing indices into `bodies`, sorted by id): adds each
    // body's gain to its accumulated priority and forgets the bodies no longer in view.
    void accumulate(std::span<const world::body> bodies, std::span<const uint32_t> view, uint32_t own_id,
                    const body_kinds& kinds, const world::world_config& config);
    // Positions in that view, in the order they go in: the own body first, then by accumulated
    // priority, highest first, ties to the lower id.
    [[nodiscard]] std::span<const uint32_t> ranked() const { return ranked_; }
    // chosen[k]: view position k went in; its priority starts again from 0.
    void sent(std::span<const uint8_t> chosen);
    // The most snapshots in a row any body of the last view has been left out of.
    [[nodiscard]] uint32_t most_left_out() const;
    // A body's accumulated priority and its snapshots left out in a row (0, 0 when not in view).
    [[nodiscard]] uint64_t priority_of(uint32_t id) const;
    [[nodiscard]] uint32_t left_out_of(uint32_t id) const;

    // One snapshot's gain of a body whose kind weighs `weight` (1 to 4: body_kinds::weight_of)
    // at squared distance d2 (m²) from the own body.
    [[nodiscard]] static uint64_t gain(uint8_t weight, float d2);

private:
    struct entry {
        uint32_t id = 0;
        uint64_t priority = 0;
        uint32_t left_out = 0;  // snapshots in a row it was left out of
    };
    const entry* find(uint32_t id) const;
    std::vector<entry> entries_;  // the last view's bodies, by position (increasing id)
    std::vector<entry> next_;
    std::vector<uint32_t> ranked_;
};

}  // namespace arena::match
