#pragma once
// The recent past of the bodies a shot can hit, for lag compensation
// (docs/LAG_COMPENSATION.md). After each step a game records where each target is and how big
// (its bounding circle); a shot made from a view `rewind` 1/256 ticks old is then tested
// against the targets where that view showed them, interpolated between the two ticks around
// that moment. It keeps world::max_rewind of ticks (and one more), so its memory is bounded by
// the targets times 66 ticks. Derived from the world's states of those ticks: a replay from the
// recording's start builds the same history (docs/DETERMINISM.md).
#include <algorithm>
#include <cstdint>
#include <deque>
#include <vector>

#include "server/world/broadphase.hpp"
#include "server/world/config.hpp"
#include "server/world/input.hpp"
#include "server/world/types.hpp"

namespace arena::rules {

class hit_history {
public:
    struct target {
        uint32_t id = 0;
        world::vec2 position{0, 0};  // m
        world::real radius = 0;      // m, bounding
    };

    // The targets after the step into `tick`, by increasing id.
    void record(uint32_t tick, std::vector<target> targets) {
        frames_.push_back({tick, std::move(targets)});
        while (frames_.size() > depth) frames_.pop_front();
    }

    // Calls f(target) with each target as it was `rewind` 1/256 ticks before `tick`: between
    // two recorded ticks, at the fraction of the way (the short way round a wrapping world);
    // a target that was not in both is taken from the one it was in. Before the oldest
    // recorded tick: the oldest.
    template <class F>
    void rewound(uint32_t tick, uint16_t rewind, const world::world_config& config, F&& f) const {
        if (frames_.empty()) return;
        const uint64_t moment = std::max<int64_t>(int64_t{tick} * 256 - rewind, 0);
        const uint32_t before = static_cast<uint32_t>(moment / 256);
        const world::real along = static_cast<world::real>(moment % 256) / 256.0f;
        const frame* a = at(before);
        const frame* b = along > 0 ? at(before + 1) : nullptr;
        if (a == nullptr) a = &frames_.front();
        if (b == nullptr || b == a) {
            for (const target& t : a->targets) f(t);
            return;
        }
        size_t k = 0;
        for (const target& t : a->targets) {
            while (k < b->targets.size() && b->targets[k].id < t.id) ++k;
            if (k < b->targets.size() && b->targets[k].id == t.id) {
                const world::vec2 d = world::displacement(t.position, b->targets[k].position, config);
                f(target{t.id, t.position + d * along, t.radius});
            } else {
                f(t);
            }
        }
    }

    [[nodiscard]] size_t ticks() const { return frames_.size(); }

    // Ticks kept: the most any input rewinds, the tick after it, and the present.
    static constexpr size_t depth = world::max_rewind / 256 + 2;

private:
    struct frame {
        uint32_t tick = 0;
        std::vector<target> targets;
    };
    const frame* at(uint32_t tick) const {
        if (frames_.empty() || tick < frames_.front().tick || tick > frames_.back().tick) return nullptr;
        const frame& f = frames_[tick - frames_.front().tick];
        return f.tick == tick ? &f : nullptr;
    }
    std::deque<frame> frames_;  // one a tick, oldest first
};

// Does a body of radius `r` moving from `from` by `step` pass within `reach` of `centre`?
// (The short way round a wrapping world.)
[[nodiscard]] inline bool sweep_hits(world::vec2 from, world::vec2 step, world::vec2 centre, world::real reach,
                                     const world::world_config& config) {
    const world::vec2 to_centre = world::displacement(from, centre, config);
    const world::real length2 = step.squaredNorm();
    world::real s = length2 > 0 ? to_centre.dot(step) / length2 : 0;
    s = std::clamp<world::real>(s, 0, 1);
    const world::vec2 closest = step * s - to_centre;
    return closest.squaredNorm() <= reach * reach;
}

}  // namespace arena::rules
