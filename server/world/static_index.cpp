#include "server/world/static_index.hpp"

#include <algorithm>
#include <cmath>

#include "server/world/integrate.hpp"
#include "server/world/trig.hpp"

namespace arena::world {

void static_index::build(std::span<const body> bodies, std::span<const shape> pool, const world_config& config) {
    entries_.clear();
    wraps_ = config.boundary == boundary::wrap;
    size_ = config.size;
    for (uint32_t i = 0; i < bodies.size(); ++i) {
        if (!bodies[i].is_static()) continue;
        // Where the step keeps it: wrapped into the world (a no-op unless the world wraps).
        body b = bodies[i];
        wrap_position(b, config);
        entry e;
        e.index = i;
        if (b.shape == no_shape) {
            e.xf = {b.position, 1, 0};
            e.box = {b.position - vec2{b.radius, b.radius}, b.position + vec2{b.radius, b.radius}};
        } else {
            const cos_sin r = compute_cos_sin(b.angle);
            e.xf = {b.position, r.c, r.s};
            e.box = compute_aabb(pool[b.shape], b.position, r.c, r.s);
        }
        entries_.push_back(e);
    }
    if (entries_.empty()) return;
    vec2 lo = entries_[0].box.lo, hi = entries_[0].box.hi;
    for (const entry& e : entries_) {
        lo = lo.cwiseMin(e.box.lo);
        hi = hi.cwiseMax(e.box.hi);
    }
    bounds_ = {lo, hi};
    // About four cells per static body, and none smaller than 1 m: a long segment spans a few
    // dozen cells at most, each listed once here.
    const vec2 size = hi - lo;
    const real target = static_cast<real>(4 * entries_.size() + 16);
    cell_ = std::max<real>(1, std::sqrt(size.x() * size.y() / target));
    while ((std::floor(size.x() / cell_) + 1) * (std::floor(size.y() / cell_) + 1) > 4 * target) cell_ *= 2;
    origin_ = lo;
    nx_ = static_cast<uint32_t>(std::floor(size.x() / cell_)) + 1;
    ny_ = static_cast<uint32_t>(std::floor(size.y() / cell_)) + 1;
    start_.assign(size_t{nx_} * ny_ + 1, 0);
    // Two passes, count then fill (a counting sort), so a cell lists its entries in index order.
    for (int pass = 0; pass < 2; ++pass) {
        if (pass == 1) {
            uint32_t sum = 0;
            for (uint32_t& s : start_) {
                const uint32_t k = s;
                s = sum;
                sum += k;
            }
            items_.assign(sum, 0);
        }
        std::vector<uint32_t> fill(pass == 1 ? start_ : std::vector<uint32_t>{});
        for (uint32_t k = 0; k < entries_.size(); ++k) {
            const aabb& box = entries_[k].box;
            for (uint32_t y = cell_y(box.lo.y()); y <= cell_y(box.hi.y()); ++y)
                for (uint32_t x = cell_x(box.lo.x()); x <= cell_x(box.hi.x()); ++x) {
                    const uint32_t c = y * nx_ + x;
                    if (pass == 0) {
                        ++start_[c];
                    } else {
                        items_[fill[c]++] = k;
                    }
                }
        }
    }
}

uint32_t static_index::cell_x(real x) const {
    const real c = (x - origin_.x()) / cell_;
    if (!(c >= 0)) return 0;
    return std::min(static_cast<uint32_t>(std::min<real>(c, 1 << 30)), nx_ - 1);
}

uint32_t static_index::cell_y(real y) const {
    const real c = (y - origin_.y()) / cell_;
    if (!(c >= 0)) return 0;
    return std::min(static_cast<uint32_t>(std::min<real>(c, 1 << 30)), ny_ - 1);
}

vec2 static_index::image_offset(uint32_t k) const {
    // Unmoved, then across one seam (x, then y), then across both.
    static constexpr int steps[image_count][2] = {{0, 0},   {-1, 0}, {1, 0},  {0, -1}, {0, 1},
                                                  {-1, -1}, {1, -1}, {-1, 1}, {1, 1}};
    return {static_cast<real>(steps[k][0]) * size_.x(), static_cast<real>(steps[k][1]) * size_.y()};
}

}  // namespace arena::world
