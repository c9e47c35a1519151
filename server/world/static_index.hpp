#pragma once
// The static bodies, in a structure of their own: a grid built once when the set of bodies
// changes, never per step, so that a 100 m platform costs its cells once instead of being
// re-binned every step like the moving bodies. A query lists the static bodies whose boxes
// overlap a box, in body index order (the contact order depends on it).
//
// In a world that wraps, each static body is kept at its position wrapped into the world (where
// the step keeps it), and a query also meets the images of the static bodies one world width
// and height away: a box near the seam touches the platforms on the other side, and a platform
// that crosses the seam holds up a body on either side.
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "server/world/body.hpp"
#include "server/world/config.hpp"
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

    // Every static body of `bodies` (shapes from `pool`), wrapped into the world when `config`'s
    // boundary wraps.
    void build(std::span<const body> bodies, std::span<const shape> pool, const world_config& config);
    bool empty() const { return entries_.empty(); }
    std::span<const entry> entries() const { return entries_; }

    // Calls visit(entry, offset) for each static body whose box, moved by `offset` (m), overlaps
    // `box`, once each and in index order. `offset` is zero unless the world wraps; then it is
    // −1, 0 or +1 world size along each axis: the static body's image that meets the box (the
    // first in image order, unmoved first, when several do). `scratch` is the caller's buffer
    // (no allocation once it has grown).
    template <class Visit>
    void query(const aabb& box, std::vector<uint32_t>& scratch, Visit&& visit) const;

    // The images a query looks at: image k is the index moved by image_offset(k); 0 is unmoved.
    static constexpr uint32_t image_count = 9;
    vec2 image_offset(uint32_t k) const;

private:
    template <class Visit>
    void query_unmoved(const aabb& box, std::vector<uint32_t>& scratch, Visit&& visit) const;
    uint32_t cell_x(real x) const;
    uint32_t cell_y(real y) const;

    std::vector<entry> entries_;   // in body index order
    vec2 origin_{0, 0};            // m
    real cell_ = 1;                // m
    uint32_t nx_ = 0, ny_ = 0;     // cells
    std::vector<uint32_t> start_;  // cell → first slot in items_ (size nx·ny + 1)
    std::vector<uint32_t> items_;  // entry numbers, by cell, increasing within a cell
    aabb bounds_;                  // m, the union of the entries' boxes
    bool wraps_ = false;           // the world wraps: queries see the images too
    vec2 size_{0, 0};              // m, the world's size (wraps_ only)
};

inline bool overlaps(const aabb& a, const aabb& b) {
    return a.lo.x() <= b.hi.x() && b.lo.x() <= a.hi.x() && a.lo.y() <= b.hi.y() && b.lo.y() <= a.hi.y();
}

inline aabb moved(const aabb& box, const vec2& by) {
    return {box.lo + by, box.hi + by};
}

template <class Visit>
void static_index::query(const aabb& box, std::vector<uint32_t>& scratch, Visit&& visit) const {
    if (entries_.empty()) return;
    const vec2 unmoved{0, 0};
    if (!wraps_) {
        query_unmoved(box, scratch, [&](const entry& e) { visit(e, unmoved); });
        return;
    }
    // The images that can reach the box: those whose bounds overlap it (most boxes, far from
    // the seam, see only the unmoved one).
    uint32_t images = 0;
    for (uint32_t k = 0; k < image_count; ++k)
        if (overlaps(moved(bounds_, image_offset(k)), box)) images |= 1u << k;
    if (images == 0) return;
    if (images == 1) {
        query_unmoved(box, scratch, [&](const entry& e) { visit(e, unmoved); });
        return;
    }
    // Entry number × 9 + image: sorted, each entry's images come together, in image order.
    scratch.clear();
    for (uint32_t k = 0; k < image_count; ++k) {
        if ((images >> k & 1) == 0) continue;
        const aabb there = moved(box, -image_offset(k));  // the box where the unmoved index sees it
        for (uint32_t y = cell_y(there.lo.y()); y <= cell_y(there.hi.y()); ++y)
            for (uint32_t x = cell_x(there.lo.x()); x <= cell_x(there.hi.x()); ++x) {
                const uint32_t c = y * nx_ + x;
                for (uint32_t i = start_[c]; i < start_[c + 1]; ++i) scratch.push_back(items_[i] * image_count + k);
            }
    }
    // Unique integers: sorting them is a total order.
    std::sort(scratch.begin(), scratch.end());
    scratch.erase(std::unique(scratch.begin(), scratch.end()), scratch.end());
    uint32_t met = ~0u;  // the last entry visited
    for (uint32_t key : scratch) {
        const uint32_t n = key / image_count;
        if (n == met) continue;
        const entry& e = entries_[n];
        const vec2 offset = image_offset(key % image_count);
        if (!overlaps(moved(e.box, offset), box)) continue;
        met = n;
        visit(e, offset);
    }
}

template <class Visit>
void static_index::query_unmoved(const aabb& box, std::vector<uint32_t>& scratch, Visit&& visit) const {
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
