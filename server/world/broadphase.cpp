#include "server/world/broadphase.hpp"

#include <algorithm>
#include <cmath>

namespace arena::world {

namespace {

uint32_t cells_along(real extent, real target) {
    const real n = std::floor(extent / target);
    return n < 1 ? 1u : static_cast<uint32_t>(std::min<real>(n, 1 << 20));
}

// Counting sort of s.items on the cell (the high half), stable, leaving s.cell_start as the
// table of where each cell's bodies start (and end: the next cell's start).
void sort_by_cell_with_table(broadphase_scratch& s, uint32_t cells) {
    s.cell_start.assign(size_t{cells} + 1, 0);
    for (uint64_t item : s.items) ++s.cell_start[item >> 32];
    uint32_t sum = 0;
    for (uint32_t c = 0; c < cells; ++c) s.cell_start[c] = sum += s.cell_start[c];  // now the ends
    s.cell_start[cells] = sum;
    // From the last body back, each cell's end moves down to its start: stable.
    for (size_t k = s.items.size(); k-- > 0;) s.swap_items[--s.cell_start[s.items[k] >> 32]] = s.items[k];
    s.items.swap(s.swap_items);
}

// Below this many bodies a comparison sort beats the radix sort's passes over its counters.
constexpr size_t small_sort_bodies = 128;

// LSD radix sort of s.items on the cell, 11 bits a pass, only the passes the largest cell needs.
// Each pass is a stable counting sort, so equal cells keep index order.
void radix_sort_by_cell(broadphase_scratch& s, uint32_t max_cell) {
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
}

// The proxy of body i: its bounding box and circle. A body with a shape gets its rotation and
// its turned shape computed here, once a step, and kept for the narrow phase. Without the
// shapes (the view index), every body is its bounding circle.
inline cell_proxy make_proxy(const body& b, uint32_t i, broadphase_scratch& s, const proxy_source& source) {
    if (b.shape == no_shape || source.pool.empty()) return {b.position, vec2{b.radius, b.radius}, b.radius, i};
    const cos_sin r = compute_cos_sin(b.angle);
    s.rotations[i] = r;
    s.turned[i] = turn(source.pool[b.shape], r.c, r.s);
    const aabb box = compute_aabb(s.turned[i], b.position);
    return {(box.lo + box.hi) * 0.5f, (box.hi - box.lo) * 0.5f, -b.radius, i};
}

}  // namespace

// Sorts the bodies by cell (stable, so in index order within a cell). A grid with a table (see
// broadphase.hpp) is sorted through it, and the table then answers "which bodies are in this
// cell" with two loads. A wrapping grid also gets its occupied cells listed as runs, and one too
// large for a table is radix-sorted: O(bodies), whatever the number of cells, since the asteroids
// preset has about 28 cells a body, nearly all empty, and walking them (with a division per
// neighbour) was 90 % of a 10k-body step.
void bucket_by_cell(std::span<const body> bodies, const grid& g, broadphase_scratch& s, const proxy_source& source) {
    const uint64_t cells = g.cell_count();
    s.items.resize(bodies.size());
    s.unsorted.resize(bodies.size());
    if (!source.pool.empty()) {
        s.rotations.resize(bodies.size());
        s.turned.resize(bodies.size());
    }
    uint32_t max_cell = 0;
    size_t n = 0;
    for (size_t i = 0; i < bodies.size(); ++i) {
        const body& b = bodies[i];
        const cell_proxy p = make_proxy(b, static_cast<uint32_t>(i), s, source);
        s.unsorted[i] = p;
        if (source.dynamic_only && b.is_static()) continue;
        const uint32_t c = cell_index(g, p.position);
        max_cell = std::max(max_cell, c);
        s.items[n++] = static_cast<uint64_t>(c) << 32 | static_cast<uint32_t>(i);
    }
    s.items.resize(n);
    s.swap_items.resize(n);
    const bool table = !g.wraps || cells <= max_table_cells(n);
    s.cell_start.clear();
    if (table) {
        sort_by_cell_with_table(s, static_cast<uint32_t>(cells));
    } else if (n <= small_sort_bodies) {
        // The same order as the stable sort by cell: an item's low half is its body index,
        // unique and increasing within a cell. A radix pass clears 2048 counters, whatever n.
        std::sort(s.items.begin(), s.items.end());
    } else {
        radix_sort_by_cell(s, max_cell);
    }
    s.proxies.resize(n);
    s.run_cell.clear();
    s.run_start.clear();
    // Gathered from the compact copy: 16 bytes a body instead of the 88-byte bodies, whose
    // random reads missed the cache in a 100k-body world.
    for (size_t k = 0; k < n; ++k) s.proxies[k] = s.unsorted[static_cast<uint32_t>(s.items[k])];
    if (!g.wraps) return;  // the table answers every question the runs would
    for (size_t k = 0; k < n; ++k) {
        const uint32_t cell = static_cast<uint32_t>(s.items[k] >> 32);
        if (s.run_cell.empty() || s.run_cell.back() != cell) {
            s.run_cell.push_back(cell);
            s.run_start.push_back(static_cast<uint32_t>(k));
        }
    }
    s.run_start.push_back(static_cast<uint32_t>(n));
}

namespace detail {

void proxies_in_index_order(std::span<const body> bodies, broadphase_scratch& s, const proxy_source& source) {
    s.proxies.clear();
    s.unsorted.resize(bodies.size());
    if (!source.pool.empty()) {
        s.rotations.resize(bodies.size());
        s.turned.resize(bodies.size());
    }
    for (size_t i = 0; i < bodies.size(); ++i) {
        s.unsorted[i] = make_proxy(bodies[i], static_cast<uint32_t>(i), s, source);
        if (!(source.dynamic_only && bodies[i].is_static())) s.proxies.push_back(s.unsorted[i]);
    }
}

}  // namespace detail

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
        g.stride = g.nx;
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
    g.stride = g.nx + 1;
    return g;
}

void find_candidate_pairs(std::span<const body> bodies, const world_config& config, broadphase_scratch& s,
                          const proxy_source& source) {
    find_candidate_pairs(bodies, make_grid(bodies, config), s, source);
}

void find_candidate_pairs(std::span<const body> bodies, const grid& g, broadphase_scratch& s,
                          const proxy_source& source) {
    s.pairs.clear();
    for_each_candidate_pair(
        bodies, g, s,
        [&s](const cell_proxy& p, const cell_proxy& q) {
            s.pairs.emplace_back(std::min(p.index, q.index), std::max(p.index, q.index));
        },
        source);
}

}  // namespace arena::world
