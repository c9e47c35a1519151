#pragma once
// Uniform-grid broadphase: candidate pairs of circles whose cells touch, in a deterministic
// order (cells in index order, bodies within a cell in id order).
#include <algorithm>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "server/world/body.hpp"
#include "server/world/config.hpp"

namespace arena::world {

// Buffers reused from step to step so that the broadphase allocates only while the world grows.
struct broadphase_scratch {
    std::vector<uint64_t> items;        // cell << 32 | body index, sorted by cell (stable)
    std::vector<uint64_t> swap_items;   // the radix sort's other buffer
    std::vector<uint32_t> count;        // radix sort: digit → next slot
    std::vector<uint32_t> sorted;       // body indices sorted by cell, stable
    std::vector<uint32_t> run_cell;     // occupied cells, increasing
    std::vector<uint32_t> run_start;    // run → first slot in `sorted` (size runs + 1)
    std::vector<std::pair<uint32_t, uint32_t>> pairs;  // candidate (a, b) indices, a < b
};

// The uniform grid over the world: cells at least as wide as the largest circle's diameter.
struct grid {
    vec2 origin{0, 0};
    vec2 cell{1, 1};  // m, width and height of a cell
    uint32_t nx = 1;
    uint32_t ny = 1;
    bool wraps = false;
};

// What the grid needs to know of the bodies: the largest radius and the bounding box of the
// centres. The world gathers it in the pass that integrates velocities, so the broadphase does
// not stream the body array once more for it.
struct body_extent {
    real max_radius = 0;  // m
    vec2 lo{0, 0};        // m, smallest centre coordinates
    vec2 hi{0, 0};        // m, largest centre coordinates
    bool any = false;     // false: no body seen yet (lo and hi meaningless)

    void add(const body& b) {
        max_radius = std::max(max_radius, b.radius);
        if (!any) {
            lo = hi = b.position;
            any = true;
            return;
        }
        lo = lo.cwiseMin(b.position);
        hi = hi.cwiseMax(b.position);
    }
};

body_extent measure_extent(std::span<const body> bodies);

// The grid that covers bodies of this extent (`count` of them) under `config`'s boundary.
grid make_grid(const body_extent& extent, size_t count, const world_config& config);
grid make_grid(std::span<const body> bodies, const world_config& config);
// The same with cells at least `cell_size` wide (m): the view index uses cells a view radius wide.
grid make_grid(const body_extent& extent, size_t count, const world_config& config, real cell_size);

// The cell of a point: points outside the grid go to its edge cells.
uint32_t cell_index(const grid& g, const vec2& p);
// Sorts the bodies by cell into scratch.sorted (stable: index order within a cell) and lists the
// occupied cells as runs (run_cell, run_start). O(bodies), whatever the number of cells.
void bucket_by_cell(std::span<const body> bodies, const grid& g, broadphase_scratch& scratch);
// The run of `cell` in scratch.run_cell, or no_run when the cell is empty.
inline constexpr uint32_t no_run = ~0u;
uint32_t find_run(const broadphase_scratch& scratch, uint32_t cell);

// Fills scratch.pairs with candidate pairs of body indices (a < b), each pair once.
void find_candidate_pairs(std::span<const body> bodies, const grid& g, broadphase_scratch& scratch);
void find_candidate_pairs(std::span<const body> bodies, const world_config& config, broadphase_scratch& scratch);

// Displacement from a to b: the shortest one when the world wraps. Inline: it runs for every
// candidate pair and every contact in every solver iteration.
inline vec2 displacement(const vec2& a, const vec2& b, const world_config& config) {
    vec2 d = b - a;
    if (config.boundary == boundary::wrap) {
        const vec2 half = config.size * 0.5f;
        if (d.x() > half.x()) d.x() -= config.size.x();
        if (d.x() < -half.x()) d.x() += config.size.x();
        if (d.y() > half.y()) d.y() -= config.size.y();
        if (d.y() < -half.y()) d.y() += config.size.y();
    }
    return d;
}

}  // namespace arena::world
