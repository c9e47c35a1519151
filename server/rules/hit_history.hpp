#pragma once
// The recent past of the bodies a shot can hit, for lag compensation
// (docs/LAG_COMPENSATION.md). After each step a game records where each target is and how big
// (its bounding circle); a shot made from a view `rewind` 1/256 ticks old is then tested
// against the targets where that view showed them, interpolated between the two ticks around
// that moment. Each tick's targets are indexed by 8 m cells, so a shot meets only the targets
// near its path: its cost does not grow with the world's. It keeps world::max_rewind of ticks (and one more), so its
// memory is bounded by the targets times 66 ticks. Derived from the world's states of those ticks: a replay from the
// recording's start builds the same history (docs/DETERMINISM.md).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <optional>
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

    // The targets after the step into `tick`, by increasing id, in a world of `config`.
    void record(uint32_t tick, std::vector<target> targets, const world::world_config& config) {
        frame f{tick, std::move(targets), {}, 0};
        for (uint32_t i = 0; i < f.targets.size(); ++i) {
            f.cells.push_back({cell_key(f.targets[i].position, config), i});
            f.reach = std::max(f.reach, f.targets[i].radius);
        }
        std::sort(f.cells.begin(), f.cells.end());
        // How far a target moved since the tick before: between two ticks a target is at most
        // that far from where the older one has it.
        if (!frames_.empty()) {
            const std::vector<target>& last = frames_.back().targets;
            size_t k = 0;
            world::real moved = 0;
            for (const target& t : f.targets) {
                while (k < last.size() && last[k].id < t.id) ++k;
                if (k < last.size() && last[k].id == t.id)
                    moved = std::max(moved, world::displacement(last[k].position, t.position, config).norm());
            }
            frames_.back().reach += moved;
        }
        frames_.push_back(std::move(f));
        while (frames_.size() > depth) frames_.pop_front();
    }

    // Calls f(target) with each target as it was `rewind` 1/256 ticks before `tick` that may be
    // within `reach` of `centre` then (and perhaps a few more), in id order: between two recorded
    // ticks, at the fraction of the way (the short way round a wrapping world); a target that
    // was not in both is taken from the older. Before the oldest recorded tick: the oldest.
    template <class F>
    void rewound_near(uint32_t tick, uint16_t rewind, world::vec2 centre, world::real reach,
                      const world::world_config& config, F&& f) const {
        if (frames_.empty()) return;
        const uint64_t moment = std::max<int64_t>(int64_t{tick} * 256 - rewind, 0);
        const uint32_t before = static_cast<uint32_t>(moment / 256);
        const world::real along = static_cast<world::real>(moment % 256) / 256.0f;
        const frame* a = at(before);
        const frame* b = along > 0 ? at(before + 1) : nullptr;
        if (a == nullptr) a = &frames_.front();
        if (b == a) b = nullptr;
        candidates_.clear();
        a->near(centre, reach + a->reach, config, candidates_);
        for (const uint32_t i : candidates_) {
            const target& t = a->targets[i];
            const target* later = b != nullptr ? b->find(t.id) : nullptr;
            if (later == nullptr) {
                f(t);
            } else {
                const world::vec2 d = world::displacement(t.position, later->position, config);
                f(target{t.id, t.position + d * along, t.radius});
            }
        }
    }

    [[nodiscard]] size_t ticks() const { return frames_.size(); }

    // Ticks kept: the most any input rewinds, the tick after it, and the present.
    static constexpr size_t depth = world::max_rewind / 256 + 2;

    // The side of a cell of the frames' index, m.
    static constexpr world::real cell = 8;

private:
    // A cell's key: its column and row (wrapped in a wrapping world), as one number.
    static int64_t cell_of(world::real v, world::real size, bool wraps) {
        int64_t c = static_cast<int64_t>(std::floor(v / cell));
        if (wraps) {
            const int64_t n = std::max<int64_t>(1, static_cast<int64_t>(std::ceil(size / cell)));
            c = ((c % n) + n) % n;
        }
        return c;
    }
    static uint64_t key(int64_t column, int64_t row) {
        return (static_cast<uint64_t>(column + (int64_t{1} << 31)) << 32) |
               static_cast<uint32_t>(row + (int64_t{1} << 31));
    }
    static uint64_t cell_key(world::vec2 p, const world::world_config& config) {
        const bool wraps = config.boundary == world::boundary::wrap;
        return key(cell_of(p.x(), config.size.x(), wraps), cell_of(p.y(), config.size.y(), wraps));
    }

    struct frame {
        uint32_t tick = 0;
        std::vector<target> targets;                       // by id
        std::vector<std::pair<uint64_t, uint32_t>> cells;  // (cell key, index in targets), sorted
        world::real reach = 0;  // the largest radius, and how far any target moves by the next tick

        const target* find(uint32_t id) const {
            const auto it = std::lower_bound(targets.begin(), targets.end(), id,
                                             [](const target& t, uint32_t v) { return t.id < v; });
            return it != targets.end() && it->id == id ? &*it : nullptr;
        }
        // The indices of the targets in the cells within `reach` of `centre`, increasing.
        void near(world::vec2 centre, world::real reach, const world::world_config& config,
                  std::vector<uint32_t>& out) const {
            const auto first = [&](world::real v) {
                return static_cast<int64_t>(std::floor((v - reach) / cell));
            };
            const auto last = [&](world::real v) {
                return static_cast<int64_t>(std::floor((v + reach) / cell));
            };
            // A window as wide as the world covers it all (each cell once).
            const int64_t columns = std::min<int64_t>(last(centre.x()) - first(centre.x()), 4096);
            const int64_t rows = std::min<int64_t>(last(centre.y()) - first(centre.y()), 4096);
            for (int64_t dx = 0; dx <= columns; ++dx) {
                for (int64_t dy = 0; dy <= rows; ++dy) {
                    const world::real x = (static_cast<world::real>(first(centre.x()) + dx) + 0.5f) * cell;
                    const world::real y = (static_cast<world::real>(first(centre.y()) + dy) + 0.5f) * cell;
                    const uint64_t k = cell_key({x, y}, config);
                    auto it = std::lower_bound(cells.begin(), cells.end(), std::pair<uint64_t, uint32_t>{k, 0});
                    for (; it != cells.end() && it->first == k; ++it) out.push_back(it->second);
                }
            }
            std::sort(out.begin(), out.end());
            out.erase(std::unique(out.begin(), out.end()), out.end());
        }
    };
    const frame* at(uint32_t tick) const {
        if (frames_.empty() || tick < frames_.front().tick || tick > frames_.back().tick) return nullptr;
        const frame& f = frames_[tick - frames_.front().tick];
        return f.tick == tick ? &f : nullptr;
    }
    std::deque<frame> frames_;  // one a tick, oldest first
    mutable std::vector<uint32_t> candidates_;
};

// Does a body moving from `from` by `step` pass within `reach` of `centre` (the short way round
// a wrapping world)? When it does: the fraction of the step at which it first comes within
// `reach` (0 when it starts there), which orders the targets one sweep meets: the one it reaches
// first is the one it hits, however far beyond the step a large target's centre lies.
[[nodiscard]] inline std::optional<world::real> sweep_hits(world::vec2 from, world::vec2 step, world::vec2 centre,
                                                           world::real reach, const world::world_config& config) {
    const world::vec2 to_centre = world::displacement(from, centre, config);
    const world::real length2 = step.squaredNorm();
    const world::real along = length2 > 0 ? to_centre.dot(step) / length2 : 0;
    const world::vec2 closest = step * std::clamp<world::real>(along, 0, 1) - to_centre;
    if (closest.squaredNorm() > reach * reach) return std::nullopt;
    const world::real outside2 = to_centre.squaredNorm() - reach * reach;
    if (outside2 <= 0 || length2 == 0) return world::real{0};
    // |from + t·step − centre| = reach: t = along − √(along² − outside²/|step|²), the smaller root.
    const world::real root2 = along * along - outside2 / length2;
    return std::clamp<world::real>(along - std::sqrt(std::max<world::real>(root2, 0)), 0, 1);
}

}  // namespace arena::rules
