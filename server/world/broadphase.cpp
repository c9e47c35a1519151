#include "server/world/broadphase.hpp"

#include <algorithm>
#include <cmath>

namespace arena::world {

namespace {

real largest_radius(std::span<const body> bodies) {
    real r = 0;
    for (const body& b : bodies) r = std::max(r, b.radius);
    return r;
}

uint32_t cells_along(real extent, real target) {
    const real n = std::floor(extent / target);
    return n < 1 ? 1u : static_cast<uint32_t>(std::min<real>(n, 1 << 20));
}

uint32_t cell_coordinate(real offset, real cell, uint32_t count) {
    const real c = std::floor(offset / cell);
    if (!(c >= 0)) return 0;  // also catches NaN, which must never get here
    return std::min(static_cast<uint32_t>(std::min<real>(c, 1 << 30)), count - 1);
}

uint32_t cell_index(const grid& g, const vec2& p) {
    const uint32_t cx = cell_coordinate(p.x() - g.origin.x(), g.cell.x(), g.nx);
    const uint32_t cy = cell_coordinate(p.y() - g.origin.y(), g.cell.y(), g.ny);
    return cy * g.nx + cx;
}

void bucket_by_cell(std::span<const body> bodies, const grid& g, broadphase_scratch& s) {
    const uint32_t cells = g.nx * g.ny;
    s.cell_of.resize(bodies.size());
    s.cell_start.assign(cells + 1, 0);
    for (size_t i = 0; i < bodies.size(); ++i) {
        s.cell_of[i] = cell_index(g, bodies[i].position);
        ++s.cell_start[s.cell_of[i] + 1];
    }
    for (uint32_t c = 0; c < cells; ++c) s.cell_start[c + 1] += s.cell_start[c];
    // Counting sort: stable, so bodies stay in id order within a cell.
    s.sorted.resize(bodies.size());
    s.cursor.assign(s.cell_start.begin(), s.cell_start.end() - 1);
    for (size_t i = 0; i < bodies.size(); ++i) s.sorted[s.cursor[s.cell_of[i]]++] = static_cast<uint32_t>(i);
}

void add_pair(broadphase_scratch& s, uint32_t a, uint32_t b) {
    s.pairs.emplace_back(std::min(a, b), std::max(a, b));
}

void all_pairs(size_t count, broadphase_scratch& s) {
    for (uint32_t a = 0; a < count; ++a)
        for (uint32_t b = a + 1; b < count; ++b) s.pairs.emplace_back(a, b);
}

}  // namespace

grid make_grid(std::span<const body> bodies, const world_config& config) {
    grid g;
    // Cells span the largest diameter plus the speculative distance: any pair that may touch
    // this step lies in the same or neighbouring cells.
    const real target = std::max<real>(2 * largest_radius(bodies) + config.speculative_distance, 1e-3f);
    if (config.boundary == boundary::wrap) {
        g.wraps = true;
        g.nx = cells_along(config.size.x(), target);
        g.ny = cells_along(config.size.y(), target);
        g.cell = {config.size.x() / static_cast<real>(g.nx), config.size.y() / static_cast<real>(g.ny)};
        return g;
    }
    vec2 lo = bodies.empty() ? vec2{0, 0} : bodies[0].position;
    vec2 hi = lo;
    for (const body& b : bodies) {
        lo = lo.cwiseMin(b.position);
        hi = hi.cwiseMax(b.position);
    }
    // Keep the grid no larger than about 4 cells a body: sparse worlds get bigger cells.
    real cell = target;
    const real limit = static_cast<real>(4 * bodies.size() + 16);
    while ((std::floor((hi.x() - lo.x()) / cell) + 1) * (std::floor((hi.y() - lo.y()) / cell) + 1) > limit) cell *= 2;
    g.origin = lo;
    g.cell = {cell, cell};
    g.nx = static_cast<uint32_t>(std::floor((hi.x() - lo.x()) / cell)) + 1;
    g.ny = static_cast<uint32_t>(std::floor((hi.y() - lo.y()) / cell)) + 1;
    return g;
}

void find_candidate_pairs(std::span<const body> bodies, const world_config& config, broadphase_scratch& s) {
    s.pairs.clear();
    const grid g = make_grid(bodies, config);
    // A wrapping grid under 3 cells wide would see one neighbour twice: test every pair.
    if (g.wraps && (g.nx < 3 || g.ny < 3)) {
        all_pairs(bodies.size(), s);
        return;
    }
    bucket_by_cell(bodies, g, s);
    // Half of the 3×3 neighbourhood, so that each pair of cells is visited once.
    static constexpr int offsets[4][2] = {{1, 0}, {-1, 1}, {0, 1}, {1, 1}};
    for (uint32_t cy = 0; cy < g.ny; ++cy) {
        for (uint32_t cx = 0; cx < g.nx; ++cx) {
            const uint32_t c = cy * g.nx + cx;
            for (uint32_t i = s.cell_start[c]; i < s.cell_start[c + 1]; ++i) {
                for (uint32_t j = i + 1; j < s.cell_start[c + 1]; ++j) add_pair(s, s.sorted[i], s.sorted[j]);
            }
            for (const auto& o : offsets) {
                int nx = static_cast<int>(cx) + o[0];
                int ny = static_cast<int>(cy) + o[1];
                if (g.wraps) {
                    nx = (nx + static_cast<int>(g.nx)) % static_cast<int>(g.nx);
                    ny = ny % static_cast<int>(g.ny);
                } else if (nx < 0 || nx >= static_cast<int>(g.nx) || ny >= static_cast<int>(g.ny)) {
                    continue;
                }
                const uint32_t n = static_cast<uint32_t>(ny) * g.nx + static_cast<uint32_t>(nx);
                for (uint32_t i = s.cell_start[c]; i < s.cell_start[c + 1]; ++i)
                    for (uint32_t j = s.cell_start[n]; j < s.cell_start[n + 1]; ++j) add_pair(s, s.sorted[i], s.sorted[j]);
            }
        }
    }
}

vec2 displacement(const vec2& a, const vec2& b, const world_config& config) {
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
