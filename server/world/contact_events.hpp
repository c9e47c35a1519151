#pragma once
// Contact events: after a step, the pairs of bodies that began touching in it, for game rules
// (a bullet hit a rock) rather than for physics. Like Jolt's contact listener made
// deterministic, they are stored and then sorted, here by the two body ids, so their order
// never depends on the broadphase's. They read the step and never change the state.
//
// A pair touches in a step when one of its contact points overlaps (separation ≤ 0) or the
// solver pushed it apart (a speculative contact that stopped a fast body just short). It
// began touching when it did not touch in the step before. Walls give no events.
#include <cstdint>
#include <span>
#include <vector>

#include "server/world/body.hpp"
#include "server/world/contacts.hpp"

namespace arena::world {

struct contact_event {
    uint32_t a = 0;           // the lower body id
    uint32_t b = 0;           // the higher body id
    vec2 normal{1, 0};        // unit, from a towards b
    real approach_speed = 0;  // m/s, how fast they closed along the normal before the solve
    real impulse = 0;         // N·s, the normal impulse the solver applied between them this step
};

class contact_event_tracker {
public:
    // Before the solve: each body pair's closing speed (the velocities the solver starts from).
    void measure_approach(std::span<const body> bodies, std::span<const contact> contacts);
    // After the solve: the pairs that began touching, sorted by (a, b); remembers this step's.
    // `sub_stepped`: the impulses are the points' step_impulse (summed over the sub-steps, see
    // soft_solver.hpp) rather than their normal_impulse.
    void collect(std::span<const body> bodies, std::span<const contact> contacts, bool sub_stepped = false);

    std::span<const contact_event> events() const { return events_; }
    // Forgets the pairs touching now, so that the next step reports them again (a world that
    // turns events on afresh).
    void reset();

private:
    std::vector<real> approach_;      // contact → closing speed (walls: 0)
    std::vector<uint64_t> touching_;  // a << 32 | b of the pairs touching in the last step, increasing
    std::vector<uint64_t> now_;       // this step's, being built
    std::vector<contact_event> events_;
};

}  // namespace arena::world
