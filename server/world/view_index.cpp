#include "server/world/view_index.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace arena::world {

void view_index::build(std::span<const body> bodies, const world_config& config, real radius) {
    config_ = config;
    radius_ = radius;
    const body_extent extent = measure_extent(bodies);
    reach_ = radius + extent.max_radius;
    // Cells half the reach: a query visits about 5×5 cells, an area twice the disc's (3×3
    // cells a reach wide would be 2.9 times), and the cells wholly inside the disc need no
    // distance test. Smaller cells cut the distance tests but cost more per cell visited.
    grid_ = make_grid(extent, bodies.size(), config, reach_ / 2);
    bucket_by_cell(bodies, grid_, scratch_);
    seen_.assign((bodies.size() + 63) / 64, 0);
}

void view_index::visit_cell(uint32_t cx, uint32_t cy, bool inside, vec2 centre, std::vector<uint32_t>& out) const {
    const uint32_t cell = cy * grid_.stride + cx;
    const slot_range slots = cell_slots(scratch_, cell);
    if (inside) {
        for (uint32_t k = slots.begin; k < slots.end; ++k) out.push_back(scratch_.proxies[k].index);
        return;
    }
    for (uint32_t k = slots.begin; k < slots.end; ++k) {
        const cell_proxy& p = scratch_.proxies[k];
        const real limit = radius_ + p.radius;
        if (displacement(centre, p.position, config_).squaredNorm() <= limit * limit) out.push_back(p.index);
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

// The cell coordinate c on the grid, [0, cells): one division per query axis; the walk then
// steps on from it without dividing.
uint32_t wrapped(int64_t c, uint32_t cells) {
    const int64_t m = c % cells;
    return static_cast<uint32_t>(m < 0 ? m + cells : m);
}

}  // namespace

void view_index::query(vec2 centre, std::vector<uint32_t>& out) {
    const size_t first_new = out.size();
    const bool wraps = grid_.wraps;
    const cell_span xs =
        covered(centre.x() - reach_, centre.x() + reach_, grid_.origin.x(), grid_.cell.x(), grid_.nx, wraps);
    const cell_span ys =
        covered(centre.y() - reach_, centre.y() + reach_, grid_.origin.y(), grid_.cell.y(), grid_.ny, wraps);
    // A cell is wholly inside when its farthest corner is within the radius of the centre:
    // every body there passes (|d| ≤ radius ≤ radius + its own radius). The corners are those
    // of the cell's copy the walk is at (cx, cy before wrapping); in a wrapping world a body's
    // shortest displacement is no longer than to that copy, so the test stays safe. Edge cells
    // never qualify: they also hold the bodies clamped into them from just outside.
    auto inside = [&](int64_t cx, int64_t cy, uint32_t wx, uint32_t wy) {
        if (wx == 0 || wy == 0 || wx + 1 >= grid_.nx || wy + 1 >= grid_.ny) return false;
        const real x0 = grid_.origin.x() + static_cast<real>(cx) * grid_.cell.x() - centre.x();
        const real y0 = grid_.origin.y() + static_cast<real>(cy) * grid_.cell.y() - centre.y();
        const real fx = std::max(std::abs(x0), std::abs(x0 + grid_.cell.x()));
        const real fy = std::max(std::abs(y0), std::abs(y0 + grid_.cell.y()));
        return fx * fx + fy * fy <= radius_ * radius_;
    };
    const uint32_t x_start = wrapped(xs.first, grid_.nx), y_start = wrapped(ys.first, grid_.ny);
    for (uint32_t j = 0, cy = y_start; j < ys.count; ++j, cy = cy + 1 == grid_.ny ? 0 : cy + 1) {
        for (uint32_t i = 0, cx = x_start; i < xs.count; ++i, cx = cx + 1 == grid_.nx ? 0 : cx + 1)
            visit_cell(cx, cy, inside(xs.first + i, ys.first + j, cx, cy), centre, out);
    }
    // Cells come in grid order, not index order, and the view must be sorted by id. A large
    // view is put in order through a bitmap of the bodies (a pass over N/64 words), a small one
    // by sorting.
    const auto found = out.begin() + static_cast<std::ptrdiff_t>(first_new);
    const size_t count = static_cast<size_t>(out.end() - found);
    if (count * 16 < seen_.size()) {
        std::sort(found, out.end());
        return;
    }
    for (auto it = found; it != out.end(); ++it) seen_[*it / 64] |= uint64_t{1} << (*it % 64);
    out.erase(found, out.end());
    for (size_t w = 0; w < seen_.size(); ++w) {
        for (uint64_t bits = seen_[w]; bits != 0; bits &= bits - 1)
            out.push_back(static_cast<uint32_t>(w * 64 + static_cast<size_t>(std::countr_zero(bits))));
        seen_[w] = 0;
    }
}

}  // namespace arena::world
