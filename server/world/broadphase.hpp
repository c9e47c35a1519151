#pragma once
// Uniform-grid broadphase: candidate pairs of bodies whose cells touch, in a deterministic
// order (cells in index order, bodies within a cell in id order). Bodies are binned by the
// centre of their bounding box, in cells at least as wide as the largest bounding circle's
// diameter. Static bodies with a shape stay out of it (static_index.hpp).
#include <algorithm>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "server/world/body.hpp"
#include "server/world/config.hpp"
#include "server/world/profile.hpp"
#include "server/world/shape.hpp"
#include "server/world/trig.hpp"

namespace arena::world {

// A body as the broadphase reads it: 24 contiguous bytes in cell order, so that testing a
// candidate pair reads two nearby proxies instead of two bodies anywhere in the array.
struct cell_proxy {
    vec2 position;   // m, the centre of the bounding box (a circle's centre)
    vec2 half;       // m, the bounding box's half extents
    real radius;     // m, the bounding circle's radius: positive for a circle, negated for any
                     // other shape (so that circle pairs keep their exact distance test)
    uint32_t index;  // in the body span

    bool is_circle() const { return radius > 0; }
    real bounding_radius() const { return radius > 0 ? radius : -radius; }
};

// Buffers reused from step to step so that the broadphase allocates only while the world grows.
struct broadphase_scratch {
    std::vector<uint64_t> items;                       // cell << 32 | body index, sorted by cell (stable)
    std::vector<uint64_t> swap_items;                  // the radix sort's other buffer
    std::vector<uint32_t> count;                       // radix sort: digit → next slot
    std::vector<cell_proxy> unsorted;                  // the bodies' proxies in index order
    std::vector<cell_proxy> proxies;                   // the bodies sorted by cell, stable (index order within a cell)
    std::vector<uint32_t> run_cell;                    // occupied cells, increasing (see bucket_by_cell)
    std::vector<uint32_t> run_start;                   // run → first slot in `proxies` (size runs + 1)
    std::vector<uint32_t> cell_start;                  // cell → first slot in `proxies` (size cells + 1); empty
                                                       // when the grid has too many cells for a table
    std::vector<std::pair<uint32_t, uint32_t>> pairs;  // candidate (a, b) indices, a < b
    std::vector<cos_sin> rotations;                    // body index → rotation, for bodies with a shape
    std::vector<turned_shape> turned;                  // body index → its shape turned, for the same
    phase_laps* laps = nullptr;                        // world::step's stopwatch, while it runs
};

// Where the broadphase finds the shapes of bodies that are not circles (body::shape indexes
// `pool`; without a pool every body is taken as its bounding circle), and whether it leaves the static bodies out (the
// world keeps them in a static_index of their own; the view index wants every body).
struct proxy_source {
    std::span<const shape> pool{};
    bool dynamic_only = false;
};

// The uniform grid over the world: cells at least as wide as the largest circle's diameter.
struct grid {
    vec2 origin{0, 0};
    vec2 cell{1, 1};  // m, width and height of a cell
    uint32_t nx = 1;
    uint32_t ny = 1;
    bool wraps = false;
    // Cell numbers per row: cell (cx, cy) is cy·stride + cx. A grid that does not wrap numbers
    // one more column and one more row, always empty, so that the cells after a body's own in
    // its row, and the three below it, are two ranges of consecutive numbers even at the edges.
    uint32_t stride = 1;

    uint64_t cell_count() const { return uint64_t{stride} * (wraps ? ny : ny + 1); }
};

// What the grid needs to know of the bodies: the largest (bounding) radius and the bounding box
// of the centres. The world adds only its dynamic bodies: a static body's extent would size the
// grid for nothing (a 100 m segment would make 100 m cells). The world gathers it in the pass that integrates
// velocities, so the broadphase does not stream the body array once more for it.
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

// The cell of a point: points outside the grid go to its edge cells. Inline: it runs for every
// body every step.
inline uint32_t cell_index(const grid& g, const vec2& p) {
    // Truncation is floor for the non-negative quotients kept; floorf was a libm call per axis.
    auto coordinate = [](real offset, real cell, uint32_t count) {
        const real c = offset / cell;
        if (!(c >= 0)) return 0u;  // also catches NaN, which must never get here
        return std::min(static_cast<uint32_t>(std::min<real>(c, 1 << 30)), count - 1);
    };
    return coordinate(p.y() - g.origin.y(), g.cell.y(), g.ny) * g.stride +
           coordinate(p.x() - g.origin.x(), g.cell.x(), g.nx);
}
// Sorts the bodies by cell into scratch.proxies (stable: index order within a cell). A grid that
// does not wrap (make_grid keeps it near 4 cells a body), or one of at most
// max_table_cells(count) cells, gets the cell table (cell_start); wrapping grids also get the
// occupied cells listed as runs (run_cell, run_start). O(bodies + table).
void bucket_by_cell(std::span<const body> bodies, const grid& g, broadphase_scratch& scratch,
                    const proxy_source& source = {});
// The largest wrapping grid that gets a cell table: a table costs a pass over its cells, so a
// sparse wrapping world (the asteroids preset has about 28 cells a body) walks the runs instead.
// The constant is small: when it was 65,536, a match of 8 ships in the asteroids preset spent
// 55 % of its tick passing over empty cells (arena-bench-matches, under perf).
inline size_t max_table_cells(size_t bodies) {
    return 8 * bodies + 1024;
}
// The run of `cell` in scratch.run_cell, or no_run when the cell is empty.
inline constexpr uint32_t no_run = ~0u;
inline uint32_t find_run(const broadphase_scratch& s, uint32_t cell) {
    const auto at = std::lower_bound(s.run_cell.begin(), s.run_cell.end(), cell);
    return at != s.run_cell.end() && *at == cell ? static_cast<uint32_t>(at - s.run_cell.begin()) : no_run;
}
// The slots of scratch.proxies that hold `cell`'s bodies: [begin, end), empty for an empty cell.
struct slot_range {
    uint32_t begin = 0;
    uint32_t end = 0;
};
// After bucket_by_cell.
inline slot_range cell_slots(const broadphase_scratch& s, uint32_t cell) {
    if (!s.cell_start.empty()) return {s.cell_start[cell], s.cell_start[cell + 1]};
    const uint32_t run = find_run(s, cell);
    return run == no_run ? slot_range{} : slot_range{s.run_start[run], s.run_start[run + 1]};
}

// Fills scratch.pairs with candidate pairs of body indices (a < b), each pair once.
// Candidates are pairs whose bounding boxes overlap (circles: whose discs overlap).
void find_candidate_pairs(std::span<const body> bodies, const grid& g, broadphase_scratch& scratch,
                          const proxy_source& source = {});
void find_candidate_pairs(std::span<const body> bodies, const world_config& config, broadphase_scratch& scratch,
                          const proxy_source& source = {});

// Calls visit(p, q) with the two cell proxies of every candidate pair (bodies in the same or
// neighbouring cells), each pair once, in the order find_candidate_pairs lists them. A template
// so that the caller's test runs inline: the contact detection's distance test per candidate,
// behind a call and a vector of pairs, was a fifth of a dense step.
template <class Visit>
void for_each_candidate_pair(std::span<const body> bodies, const grid& g, broadphase_scratch& scratch, Visit&& visit,
                             const proxy_source& source = {});

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

namespace detail {

// The run of `cell`, moving `cursor` to it. The next row's targets grow with the current cell,
// except that a cell's (+1, +1) may lie past the next cell's (−1, +1): the cursor steps back at
// most two runs, so the whole walk stays O(runs).
inline uint32_t find_run_from(const broadphase_scratch& s, uint32_t& cursor, uint32_t cell) {
    const uint32_t runs = static_cast<uint32_t>(s.run_cell.size());
    while (cursor > 0 && s.run_cell[cursor - 1] >= cell) --cursor;
    while (cursor < runs && s.run_cell[cursor] < cell) ++cursor;
    return cursor < runs && s.run_cell[cursor] == cell ? cursor : no_run;
}

// scratch.proxies in body index order, unsorted: a wrapping grid under 3 cells wide would see
// one neighbour twice, so every pair is tested instead.
void proxies_in_index_order(std::span<const body> bodies, broadphase_scratch& s, const proxy_source& source);

}  // namespace detail

template <class Visit>
void for_each_candidate_pair(std::span<const body> bodies, const grid& g, broadphase_scratch& s, Visit&& visit,
                             const proxy_source& source) {
    if (g.wraps && (g.nx < 3 || g.ny < 3)) {
        detail::proxies_in_index_order(bodies, s, source);
        if (s.laps) s.laps->lap(step_phase::broadphase);
        for (size_t a = 0; a < s.proxies.size(); ++a)
            for (size_t b = a + 1; b < s.proxies.size(); ++b) visit(s.proxies[a], s.proxies[b]);
        return;
    }
    bucket_by_cell(bodies, g, s, source);
    if (s.laps) s.laps->lap(step_phase::broadphase);
    // Each body in cell order meets the bodies after it in its own cell, then those of half of
    // its 3×3 neighbourhood in cell order: (+1, 0), (−1, +1), (0, +1), (+1, +1). Each pair of
    // cells is visited once, so each pair of bodies is.
    const uint32_t n = static_cast<uint32_t>(s.proxies.size());
    if (!g.wraps) {
        // With the table and the empty edge column and row, that is two ranges of slots, walked
        // as one loop: each loop's exit is a branch the predictor cannot learn.
        for (uint32_t k = 0; k < n; ++k) {
            const uint32_t c = static_cast<uint32_t>(s.items[k] >> 32);
            const uint32_t right = s.cell_start[c + 2] - (k + 1);  // own later bodies, then (+1, 0)
            const uint32_t below_begin = s.cell_start[c + g.stride - 1];
            const uint32_t count = right + (s.cell_start[c + g.stride + 2] - below_begin);
            for (uint32_t t = 0; t < count; ++t) {
                const uint32_t j = t < right ? k + 1 + t : below_begin + (t - right);
                visit(s.proxies[k], s.proxies[j]);
            }
        }
        return;
    }
    // A wrapping grid: the four neighbours, taken modulo the grid, are looked up once per
    // occupied cell, in the table or among the runs.
    static constexpr int offsets[4][2] = {{1, 0}, {-1, 1}, {0, 1}, {1, 1}};
    const uint32_t runs = static_cast<uint32_t>(s.run_cell.size());
    uint32_t below = 0;               // cursor for the next row's cells, which grow with the current cell
    uint32_t row = 0, row_start = 0;  // the current cell's row, found by stepping (no division)
    for (uint32_t r = 0; r < runs; ++r) {
        const uint32_t c = s.run_cell[r];
        while (c - row_start >= g.stride) {
            ++row;
            row_start += g.stride;
        }
        const int cx = static_cast<int>(c - row_start);
        const int cy = static_cast<int>(row);
        slot_range neighbours[4];
        for (int k = 0; k < 4; ++k) {
            int nx = cx + offsets[k][0];
            int ny = cy + offsets[k][1];
            const bool crosses = nx < 0 || nx >= static_cast<int>(g.nx) || ny >= static_cast<int>(g.ny);
            if (crosses) {
                nx = (nx + static_cast<int>(g.nx)) % static_cast<int>(g.nx);
                ny = ny % static_cast<int>(g.ny);
            }
            const uint32_t cell = static_cast<uint32_t>(ny) * g.stride + static_cast<uint32_t>(nx);
            if (!s.cell_start.empty() || crosses) {
                neighbours[k] = cell_slots(s, cell);
            } else if (offsets[k][1] == 0) {
                if (r + 1 < runs && s.run_cell[r + 1] == cell) neighbours[k] = {s.run_start[r + 1], s.run_start[r + 2]};
            } else if (const uint32_t run = detail::find_run_from(s, below, cell); run != no_run) {
                neighbours[k] = {s.run_start[run], s.run_start[run + 1]};
            }
        }
        const uint32_t end = s.run_start[r + 1];
        for (uint32_t i = s.run_start[r]; i < end; ++i) {
            for (uint32_t j = i + 1; j < end; ++j) visit(s.proxies[i], s.proxies[j]);
            for (const slot_range& q : neighbours)
                for (uint32_t j = q.begin; j < q.end; ++j) visit(s.proxies[i], s.proxies[j]);
        }
    }
}

}  // namespace arena::world
