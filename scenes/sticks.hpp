#pragma once
// Scripted inputs: the sticks that drive players in the replay tests, the benchmarks and the
// bots. Each draws from the world's rng in a fixed order, so a seed always gives the same
// inputs.
#include "server/world/input.hpp"
#include "server/world/rng.hpp"

namespace arena::scenes {

// A human's stick: held for a while, then moved. In about one tick of 20 it takes a new thrust
// and turn, each uniform in [-1, 1]; buttons are left alone. True when it moved.
bool move_stick_now_and_then(world::rng& r, world::player_input& stick);

// A stick that wanders by small steps, smooth enough to look like steering rather than noise:
// thrust in [-0.2, 1] (mostly forward), turn in [-1, 1], an impulse about once in 90 ticks.
class wandering_stick {
public:
    world::player_input next(world::rng& r);

private:
    float thrust_ = 0;
    float turn_ = 0;
};

}  // namespace arena::scenes
