#pragma once
// The static bodies, in a structure of their own: a grid built once when the set of bodies
// changes, never per step, so that a 100 m platform costs its cells once instead of being
// re-binned every step like the moving bodies. A query lists the static bodies whose boxes
// overlap a box, in body index order (the contact order depends on it).
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "server/world/body.hpp"
#include "server/world/manifold.hpp"
#include "server/world/shape.hpp"

namespace arena::world {

class static_index {
public:
    struct entry {
        aabb box;        // m
        transform xf;    // the body's place (static: it never changes)
        uint32_t index;  // in the body span
    };

    // Every static body of `bodies` (shapes from `pool`).
    void build(std::span<const body> bodies, std::span<const shape> pool);
    bool empty() const { return entries_.empty(); }
    std::span<const entry> entries() const { return entries_; }

    // Calls visit(entry) for each static body whose box overlaps `box`, in index order.
    // `scratch` is the caller's buffer (no allocation once it has grown).
    template <class Visit>
    void query(const aabb& box, std::vector<uint32_t>& scratch, Visit&& visit) const;

private:
    uint32_t cell_x(real x) const;
    uint32_t cell_y(real y) const;

    std::vector<entry> entries_;   // in body index order
    vec2 origin_{0, 0};            // m
    real cell_ = 1;                // m
    uint32_t nx_ = 0, ny_ = 0;     // cells
    std::vector<uint32_t> start_;  // cell → first slot in items_ (size nx·ny + 1)
    std::vector<uint32_t> items_;  // entry numbers, by cell, increasing within a cell
};

inline bool overlaps(const aabb& a, const aabb& b) {
    return a.lo.x() <= b.hi.x() && b.lo.x() <= a.hi.x() && a.lo.y() <= b.hi.y() && b.lo.y() <= a.hi.y();
}

template <class Visit>
void static_index::query(const aabb& box, std::vector<uint32_t>& scratch, Visit&& visit) const {
    if (entries_.empty()) return;
    const uint32_t x0 = cell_x(box.lo.x()), x1 = cell_x(box.hi.x());
    const uint32_t y0 = cell_y(box.lo.y()), y1 = cell_y(box.hi.y());
    if (x0 == x1 && y0 == y1) {
        // One cell (the common case): its list is already in order and without repeats.
        const uint32_t c = y0 * nx_ + x0;
        for (uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
            const entry& e = entries_[items_[k]];
            if (overlaps(e.box, box)) visit(e);
        }
        return;
    }
    scratch.clear();
    for (uint32_t y = y0; y <= y1; ++y)
        for (uint32_t x = x0; x <= x1; ++x) {
            const uint32_t c = y * nx_ + x;
            for (uint32_t k = start_[c]; k < start_[c + 1]; ++k) scratch.push_back(items_[k]);
        }
    // Entry numbers are unique integers: sorting them is a total order.
    std::sort(scratch.begin(), scratch.end());
    scratch.erase(std::unique(scratch.begin(), scratch.end()), scratch.end());
    for (uint32_t k : scratch) {
        const entry& e = entries_[k];
        if (overlaps(e.box, box)) visit(e);
    }
}

}  // namespace arena::world
