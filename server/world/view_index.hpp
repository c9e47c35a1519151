#pragma once
// Interest management: which bodies a player can see. The server asks once per snapshot per
// client, so the index is built once per snapshot over the current positions, on the
// broadphase's grid machinery with cells at least a view radius wide: a query then visits
// about 3×3 occupied cells instead of scanning every body.
#include <cstdint>
#include <span>
#include <vector>

#include "server/world/broadphase.hpp"

namespace arena::world {

class view_index {
public:
    // Indexes the bodies for queries of this radius (m, > 0).
    void build(std::span<const body> bodies, const world_config& config, real radius);

    // Appends to `out`, in increasing index order (the bodies' id order), every body whose
    // circle comes within the radius of `centre`: |centre − position| ≤ radius + body radius,
    // the shortest way round in a wrapping world, as they were when build() indexed them.
    // Not const: it reuses scratch space (one index, one thread).
    void query(vec2 centre, std::vector<uint32_t>& out);

private:
    // `inside`: the whole cell lies within the radius, so every body in it is seen.
    void visit_cell(uint32_t cx, uint32_t cy, bool inside, vec2 centre, std::vector<uint32_t>& out) const;

    world_config config_;
    grid grid_;
    broadphase_scratch scratch_;
    real radius_ = 0;
    real reach_ = 0;              // radius + the largest body radius: how far a visible centre can be
    std::vector<uint64_t> seen_;  // one bit per body, all zero between queries
};

}  // namespace arena::world
