#include "server/world/view_index.hpp"

#include <algorithm>
#include <cmath>

namespace arena::world {

void view_index::build(std::span<const body> bodies, const world_config& config, real radius) {
    config_ = config;
    radius_ = radius;
    const body_extent extent = measure_extent(bodies);
    reach_ = radius + extent.max_radius;
    grid_ = make_grid(extent, bodies.size(), config, reach_);
    bucket_by_cell(bodies, grid_, scratch_);
}

void view_index::visit_cell(std::span<const body> bodies, uint32_t cx, uint32_t cy, vec2 centre,
                            std::vector<uint32_t>& out) const {
    const uint32_t run = find_run(scratch_, cy * grid_.nx + cx);
    if (run == no_run) return;
    for (uint32_t k = scratch_.run_start[run]; k < scratch_.run_start[run + 1]; ++k) {
        const uint32_t i = scratch_.sorted[k];
        const real limit = radius_ + bodies[i].radius;
        if (displacement(centre, bodies[i].position, config_).squaredNorm() <= limit * limit) out.push_back(i);
    }
}

namespace {

// The cell coordinates [first, first + count) a segment [lo, hi] of one axis covers. A
// wrapping axis takes them modulo `cells`; a closed one clamps, as cell_index() does.
struct cell_span {
    int64_t first = 0;
    uint32_t count = 0;
};

cell_span covered(real lo, real hi, real origin, real cell, uint32_t cells, bool wraps) {
    int64_t a = static_cast<int64_t>(std::floor((lo - origin) / cell));
    int64_t b = static_cast<int64_t>(std::floor((hi - origin) / cell));
    if (wraps) {
        if (b - a + 1 >= cells) return {0, cells};
        return {a, static_cast<uint32_t>(b - a + 1)};
    }
    a = std::clamp<int64_t>(a, 0, cells - 1);
    b = std::clamp<int64_t>(b, 0, cells - 1);
    return {a, static_cast<uint32_t>(b - a + 1)};
}

uint32_t wrapped(int64_t c, uint32_t cells) {
    const int64_t m = c % cells;
    return static_cast<uint32_t>(m < 0 ? m + cells : m);
}

}  // namespace

void view_index::query(std::span<const body> bodies, vec2 centre, std::vector<uint32_t>& out) const {
    const size_t first_new = out.size();
    const bool wraps = grid_.wraps;
    const cell_span xs = covered(centre.x() - reach_, centre.x() + reach_, grid_.origin.x(), grid_.cell.x(), grid_.nx, wraps);
    const cell_span ys = covered(centre.y() - reach_, centre.y() + reach_, grid_.origin.y(), grid_.cell.y(), grid_.ny, wraps);
    for (uint32_t j = 0; j < ys.count; ++j) {
        const uint32_t cy = wrapped(ys.first + j, grid_.ny);
        for (uint32_t i = 0; i < xs.count; ++i) visit_cell(bodies, wrapped(xs.first + i, grid_.nx), cy, centre, out);
    }
    // Cells come in grid order, not index order: the view must be sorted by id.
    std::sort(out.begin() + static_cast<std::ptrdiff_t>(first_new), out.end());
}

}  // namespace arena::world
