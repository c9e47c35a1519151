#include "server/world/broadphase.hpp"

#include <algorithm>
#include <cmath>

namespace arena::world {

namespace {

uint32_t cells_along(real extent, real target) {
    const real n = std::floor(extent / target);
    return n < 1 ? 1u : static_cast<uint32_t>(std::min<real>(n, 1 << 20));
}

uint32_t cell_coordinate(real offset, real cell, uint32_t count) {
    const real c = std::floor(offset / cell);
    if (!(c >= 0)) return 0;  // also catches NaN, which must never get here
    return std::min(static_cast<uint32_t>(std::min<real>(c, 1 << 30)), count - 1);
}

}  // namespace

uint32_t cell_index(const grid& g, const vec2& p) {
    const uint32_t cx = cell_coordinate(p.x() - g.origin.x(), g.cell.x(), g.nx);
    const uint32_t cy = cell_coordinate(p.y() - g.origin.y(), g.cell.y(), g.ny);
    return cy * g.nx + cx;
}

namespace {

// The run of `cell`, moving `cursor` to it. The next row's targets grow with the current cell,
// except that a cell's (+1, +1) may lie past the next cell's (−1, +1): the cursor steps back at
// most two runs, so the whole walk stays O(runs).
uint32_t find_run_from(const broadphase_scratch& s, uint32_t& cursor, uint32_t cell) {
    const uint32_t runs = static_cast<uint32_t>(s.run_cell.size());
    while (cursor > 0 && s.run_cell[cursor - 1] >= cell) --cursor;
    while (cursor < runs && s.run_cell[cursor] < cell) ++cursor;
    return cursor < runs && s.run_cell[cursor] == cell ? cursor : no_run;
}

void add_pair(broadphase_scratch& s, uint32_t a, uint32_t b) {
    s.pairs.emplace_back(std::min(a, b), std::max(a, b));
}

void all_pairs(size_t count, broadphase_scratch& s) {
    for (uint32_t a = 0; a < count; ++a)
        for (uint32_t b = a + 1; b < count; ++b) s.pairs.emplace_back(a, b);
}

}  // namespace

// Sorts the bodies by cell (stable, so in index order within a cell) and lists the occupied
// cells as runs. Work is O(bodies), whatever the number of cells: the asteroids preset has about
// 28 cells a body, nearly all empty, and walking them (with a division per neighbour) was 90 %
// of a 10k-body step.
void bucket_by_cell(std::span<const body> bodies, const grid& g, broadphase_scratch& s) {
    const size_t n = bodies.size();
    s.items.resize(n);
    s.swap_items.resize(n);
    uint32_t max_cell = 0;
    for (size_t i = 0; i < n; ++i) {
        const uint32_t c = cell_index(g, bodies[i].position);
        max_cell = std::max(max_cell, c);
        s.items[i] = static_cast<uint64_t>(c) << 32 | static_cast<uint32_t>(i);
    }
    // LSD radix sort on the cell (the high half), 11 bits a pass, only the passes the largest
    // cell needs. Each pass is a stable counting sort, so equal cells keep index order.
    constexpr uint32_t digit_bits = 11, digits = 1u << digit_bits;
    s.count.resize(digits);
    for (uint32_t shift = 0; shift < 32 && (max_cell >> shift) != 0; shift += digit_bits) {
        std::fill(s.count.begin(), s.count.end(), 0u);
        for (uint64_t item : s.items) ++s.count[(item >> (32 + shift)) & (digits - 1)];
        uint32_t sum = 0;
        for (uint32_t& c : s.count) {
            const uint32_t k = c;
            c = sum;
            sum += k;
        }
        for (uint64_t item : s.items) s.swap_items[s.count[(item >> (32 + shift)) & (digits - 1)]++] = item;
        s.items.swap(s.swap_items);
    }
    s.sorted.resize(n);
    s.run_cell.clear();
    s.run_start.clear();
    for (size_t k = 0; k < n; ++k) {
        const uint32_t cell = static_cast<uint32_t>(s.items[k] >> 32);
        s.sorted[k] = static_cast<uint32_t>(s.items[k]);
        if (s.run_cell.empty() || s.run_cell.back() != cell) {
            s.run_cell.push_back(cell);
            s.run_start.push_back(static_cast<uint32_t>(k));
        }
    }
    s.run_start.push_back(static_cast<uint32_t>(n));
}

// The run of `cell`, searching the whole list (for neighbours across a wrapped edge).
uint32_t find_run(const broadphase_scratch& s, uint32_t cell) {
    const auto at = std::lower_bound(s.run_cell.begin(), s.run_cell.end(), cell);
    return at != s.run_cell.end() && *at == cell ? static_cast<uint32_t>(at - s.run_cell.begin()) : no_run;
}

body_extent measure_extent(std::span<const body> bodies) {
    body_extent e;
    for (const body& b : bodies) e.add(b);
    return e;
}

grid make_grid(std::span<const body> bodies, const world_config& config) {
    return make_grid(measure_extent(bodies), bodies.size(), config);
}

grid make_grid(const body_extent& extent, size_t count, const world_config& config) {
    // Cells span the largest diameter plus the speculative distance: any pair that may touch
    // this step lies in the same or neighbouring cells.
    return make_grid(extent, count, config, 2 * extent.max_radius + config.speculative_distance);
}

grid make_grid(const body_extent& extent, size_t count, const world_config& config, real cell_size) {
    grid g;
    const real target = std::max<real>(cell_size, 1e-3f);
    if (config.boundary == boundary::wrap) {
        g.wraps = true;
        g.nx = cells_along(config.size.x(), target);
        g.ny = cells_along(config.size.y(), target);
        g.cell = {config.size.x() / static_cast<real>(g.nx), config.size.y() / static_cast<real>(g.ny)};
        return g;
    }
    const vec2 lo = extent.any ? extent.lo : vec2{0, 0};
    const vec2 hi = extent.any ? extent.hi : vec2{0, 0};
    // Keep the grid no larger than about 4 cells a body: sparse worlds get bigger cells.
    real cell = target;
    const real limit = static_cast<real>(4 * count + 16);
    while ((std::floor((hi.x() - lo.x()) / cell) + 1) * (std::floor((hi.y() - lo.y()) / cell) + 1) > limit) cell *= 2;
    g.origin = lo;
    g.cell = {cell, cell};
    g.nx = static_cast<uint32_t>(std::floor((hi.x() - lo.x()) / cell)) + 1;
    g.ny = static_cast<uint32_t>(std::floor((hi.y() - lo.y()) / cell)) + 1;
    return g;
}

void find_candidate_pairs(std::span<const body> bodies, const world_config& config, broadphase_scratch& s) {
    find_candidate_pairs(bodies, make_grid(bodies, config), s);
}

void find_candidate_pairs(std::span<const body> bodies, const grid& g, broadphase_scratch& s) {
    s.pairs.clear();
    // A wrapping grid under 3 cells wide would see one neighbour twice: test every pair.
    if (g.wraps && (g.nx < 3 || g.ny < 3)) {
        all_pairs(bodies.size(), s);
        return;
    }
    bucket_by_cell(bodies, g, s);
    // Occupied cells in index order; for each, its own pairs, then half of its 3×3
    // neighbourhood in the order (+1, 0), (−1, +1), (0, +1), (+1, +1), so that each pair of
    // cells is visited once. Empty cells add no pair, so skipping them keeps the pair order
    // (and hence the contact order and the results) exactly as a walk over every cell.
    static constexpr int offsets[4][2] = {{1, 0}, {-1, 1}, {0, 1}, {1, 1}};
    const uint32_t runs = static_cast<uint32_t>(s.run_cell.size());
    uint32_t below = 0;  // cursor for the next row's cells, which grow with the current cell
    uint32_t row = 0, row_start = 0;  // the current cell's row, found by stepping (no division)
    for (uint32_t r = 0; r < runs; ++r) {
        const uint32_t c = s.run_cell[r];
        while (c - row_start >= g.nx) {
            ++row;
            row_start += g.nx;
        }
        const uint32_t begin = s.run_start[r], end = s.run_start[r + 1];
        for (uint32_t i = begin; i < end; ++i)
            for (uint32_t j = i + 1; j < end; ++j) add_pair(s, s.sorted[i], s.sorted[j]);
        const int cx = static_cast<int>(c - row_start);
        const int cy = static_cast<int>(row);
        for (const auto& o : offsets) {
            int nx = cx + o[0];
            int ny = cy + o[1];
            const bool crosses = nx < 0 || nx >= static_cast<int>(g.nx) || ny >= static_cast<int>(g.ny);
            if (crosses && !g.wraps) continue;
            if (crosses) {
                nx = (nx + static_cast<int>(g.nx)) % static_cast<int>(g.nx);
                ny = ny % static_cast<int>(g.ny);
            }
            const uint32_t n = static_cast<uint32_t>(ny) * g.nx + static_cast<uint32_t>(nx);
            uint32_t q;
            if (crosses) {
                q = find_run(s, n);
            } else if (o[1] == 0) {
                q = r + 1 < runs && s.run_cell[r + 1] == n ? r + 1 : no_run;
            } else {
                q = find_run_from(s, below, n);
            }
            if (q == no_run) continue;
            for (uint32_t i = begin; i < end; ++i)
                for (uint32_t j = s.run_start[q]; j < s.run_start[q + 1]; ++j) add_pair(s, s.sorted[i], s.sorted[j]);
        }
    }
}

}  // namespace arena::world
