// The world's bodies: placing a config's bodies, adding and removing them between steps,
// spawning players and rocks at free spots drawn from the world's rng, finding one by id.
// Bodies stay sorted by id, so that every pass over them runs in the same order everywhere.
#include <algorithm>

#include "server/world/spawn_grid.hpp"
#include "server/world/trig.hpp"
#include "server/world/world.hpp"

namespace arena::world {

namespace {

bool less_by_id(const body& b, uint32_t id) {
    return b.id < id;
}

}  // namespace

// A config that passed the config checks makes every body; one that did not (a program that
// built a bad config) loses the bodies whose shapes cannot be made, rather than the process.
void world::place_bodies() {
    for (const body_config& bc : config_.bodies) {
        if (bc.shape.type == shape_type::chain) {
            std::vector<vec2> points;
            const cos_sin r = compute_cos_sin(bc.angle);
            for (const vec2& p : bc.shape.points)
                points.push_back(bc.position + vec2{r.c * p.x() - r.s * p.y(), r.s * p.x() + r.c * p.y()});
            add_chain(points, bc.material);
            continue;
        }
        const result<centred_shape> made = make_shape(bc.shape);
        if (!made) continue;  // the config's loader refused it already, naming the field
        const shape& s = made.value.geometry;
        const vec2 centre = made.value.centre;
        body_material material = bc.material;
        const bool is_static = bc.is_static || bc.shape.type == shape_type::segment;
        if (is_static) {
            material.density = 0;
            material.mass = 0;
        }
        const cos_sin r = compute_cos_sin(bc.angle);
        const vec2 at = bc.position + vec2{r.c * centre.x() - r.s * centre.y(), r.s * centre.x() + r.c * centre.y()};
        body b = make_body(material, s, at);
        b.angle = wrap_angle(bc.angle);
        if (!is_static) b.velocity = bc.velocity;
        if (!add_body(b, s)) return;
    }
}

std::optional<uint32_t> world::add_body(body b) {
    if (bodies_.size() >= config_.max_bodies) return std::nullopt;
    if (b.id == 0) {
        b.id = next_id_;
    } else if (find(b.id)) {
        return std::nullopt;
    }
    next_id_ = std::max(next_id_, b.id + 1);
    auto at = std::lower_bound(bodies_.begin(), bodies_.end(), b.id, less_by_id);
    bodies_.insert(at, b);
    statics_dirty_ = true;  // indices moved
    return b.id;
}

std::optional<uint32_t> world::add_body(body b, const shape& s) {
    if (s.kind == shape_kind::circle) {
        b.radius = s.radius;
        b.shape = no_shape;
        return add_body(b);
    }
    if (bodies_.size() >= config_.max_bodies) return std::nullopt;
    if (b.id != 0 && find(b.id)) return std::nullopt;
    if (free_shapes_.empty()) {
        b.shape = static_cast<uint32_t>(shapes_.size());
        shapes_.push_back(s);
    } else {
        b.shape = free_shapes_.back();
        free_shapes_.pop_back();
        shapes_[b.shape] = s;
    }
    b.radius = bounding_radius(s);
    return add_body(b);
}

std::optional<std::vector<uint32_t>> world::add_chain(std::span<const vec2> points, const body_material& material) {
    // A chain whose last point is its first is a loop: its first and last segments are
    // neighbours too. In a wrapping world so is one whose last point is its first one world
    // width or height on (a floor all the way round): its ends meet across the seam.
    const size_t n = points.size();
    const vec2 round = n >= 2 ? vec2{points.back() - points.front()} : vec2{0, 0};
    auto whole_turn = [](real d, real size) {
        return d == 0 || d == size || d == -size;
    };
    const bool around = config_.boundary == boundary::wrap && round != vec2{0, 0} &&
                        whole_turn(round.x(), config_.size.x()) && whole_turn(round.y(), config_.size.y());
    const bool loop = (n >= 4 && round == vec2{0, 0}) || (n >= 3 && around);
    // A segment of no length has no normal: refused before any body is added.
    for (size_t k = 0; k + 1 < n; ++k)
        if (points[k] == points[k + 1]) return std::nullopt;
    std::vector<uint32_t> ids;
    for (size_t k = 0; k + 1 < n; ++k) {
        const vec2 mid = (points[k] + points[k + 1]) * 0.5f;
        body b;
        b.mass = 0;
        b.inv_mass = 0;
        b.inertia = 0;
        b.inv_inertia = 0;
        b.restitution = material.restitution;
        b.friction = material.friction;
        b.drag_area = 0;
        b.position = mid;
        shape s = make_segment(points[k] - mid, points[k + 1] - mid);
        s.chain.linked = true;
        if (k > 0 || loop) {
            s.chain.has_prev = true;
            s.chain.prev = k > 0 ? vec2{points[k - 1] - mid} : vec2{points[n - 2] - round - mid};
        }
        if (k + 2 < n || loop) {
            s.chain.has_next = true;
            s.chain.next = k + 2 < n ? vec2{points[k + 2] - mid} : vec2{points[1] + round - mid};
        }
        const std::optional<uint32_t> id = add_body(b, s);
        if (!id) return std::nullopt;
        ids.push_back(*id);
    }
    return ids;
}

std::optional<body_id> world::spawn_player(player_id owner) {
    const body_id id = spawn_players({&owner, 1})[0];
    return id ? std::optional<body_id>(id) : std::nullopt;
}

std::vector<body_id> world::spawn_players(std::span<const player_id> owners) {
    std::vector<body_id> ids;
    ids.reserve(owners.size());
    if (owners.empty()) return ids;
    // One grid for every spawn of the batch: its cells are wider than any two radii together.
    const real player_radius = config_.player.radius;
    real widest = player_radius;
    for (const body& b : bodies_) widest = std::max(widest, b.radius);
    spawn_grid grid(config_, widest + player_radius, bodies_.size() + owners.size());
    for (const body& b : bodies_) grid.add(b.position, b.radius);
    for (const player_id owner : owners) {
        if (bodies_.size() >= config_.max_bodies) {
            ids.emplace_back();
            continue;
        }
        body b = make_body(config_.player, random_free_position(player_radius, [&grid](const vec2& p, real r) {
                               return grid.is_free(p, r);
                           }));
        b.owner = owner.value();
        const auto id = add_body(b);
        if (id) grid.add(b.position, b.radius);
        ids.emplace_back(id.value_or(0));
    }
    return ids;
}

void world::remove_bodies(std::span<const body_id> ids) {
    if (ids.empty()) return;
    std::vector<uint32_t> sorted;
    sorted.reserve(ids.size());
    for (const body_id id : ids) sorted.push_back(id.value());
    std::sort(sorted.begin(), sorted.end());
    auto removed = [&sorted](const body& b) {
        return std::binary_search(sorted.begin(), sorted.end(), b.id);
    };
    // Their shapes back to the pool, in id order (the pool's reuse order is part of the state).
    for (const body& b : bodies_)
        if (b.shape != no_shape && removed(b)) free_shapes_.push_back(b.shape);
    std::erase_if(bodies_, removed);
    statics_dirty_ = true;  // indices moved
}

bool world::remove_body(uint32_t id) {
    auto at = std::lower_bound(bodies_.begin(), bodies_.end(), id, less_by_id);
    if (at == bodies_.end() || at->id != id) return false;
    if (at->shape != no_shape) free_shapes_.push_back(at->shape);
    bodies_.erase(at);
    statics_dirty_ = true;  // indices moved
    return true;
}

body* world::find(uint32_t id) {
    auto at = std::lower_bound(bodies_.begin(), bodies_.end(), id, less_by_id);
    return at != bodies_.end() && at->id == id ? &*at : nullptr;
}

const body* world::find(uint32_t id) const {
    return const_cast<world*>(this)->find(id);
}

void world::spawn_rocks() {
    const rock_config& rocks = config_.rocks;
    if (rocks.count == 0) return;
    // A grid of cells two largest radii wide, so that each spawn tests only its neighbours.
    const real cell = 2 * rocks.max_radius;
    const int nx = std::max(1, static_cast<int>(std::min<real>(config_.size.x() / cell, 4096)));
    const int ny = std::max(1, static_cast<int>(std::min<real>(config_.size.y() / cell, 4096)));
    std::vector<std::vector<uint32_t>> cells(static_cast<size_t>(nx) * static_cast<size_t>(ny));
    auto cell_of = [&](const vec2& p, int& cx, int& cy) {
        cx = std::clamp(static_cast<int>(p.x() / config_.size.x() * static_cast<real>(nx)), 0, nx - 1);
        cy = std::clamp(static_cast<int>(p.y() / config_.size.y() * static_cast<real>(ny)), 0, ny - 1);
    };
    std::vector<body> placed;
    std::vector<shape> placed_shapes;  // polygon rocks: placed[k].shape indexes this until they join
    // The config's bodies (platforms, crates: few) by their bounding boxes, then the rocks so far.
    std::vector<aabb> fixed;
    for (const body& b : bodies_) {
        const cos_sin r = compute_cos_sin(b.angle);
        fixed.push_back(compute_aabb(shape_of(b), b.position, r.c, r.s));
    }
    auto is_free = [&](const vec2& p, real radius) {
        const aabb own{p - vec2{radius, radius}, p + vec2{radius, radius}};
        for (const aabb& box : fixed)
            if (overlaps(box, own)) return false;
        int cx, cy;
        cell_of(p, cx, cy);
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                const int x = (cx + dx + nx) % nx;
                const int y = (cy + dy + ny) % ny;
                for (uint32_t k : cells[static_cast<size_t>(y) * nx + x]) {
                    const real reach = placed[k].radius + radius;
                    if (displacement(p, placed[k].position, config_).squaredNorm() < reach * reach) return false;
                }
            }
        }
        return true;
    };
    // max_bodies counts the rocks placed so far, which join bodies_ only after the loop.
    for (uint32_t i = 0; i < rocks.count && bodies_.size() + placed.size() < config_.max_bodies; ++i) {
        body_material material = rocks.material;
        material.radius = rng_.uniform(rocks.min_radius, rocks.max_radius);
        body b = make_body(material, random_free_position(material.radius, is_free));
        // One draw per statement: argument evaluation order differs between compilers.
        const real vx = rng_.uniform(-rocks.max_speed, rocks.max_speed);
        const real vy = rng_.uniform(-rocks.max_speed, rocks.max_speed);
        b.velocity = {vx, vy};
        if (rocks.polygon_vertices >= 3) {
            const std::optional<shape> rock = irregular_polygon(material.radius);
            if (rock) {
                const body shaped = make_body(material, *rock, b.position);
                b.mass = shaped.mass;
                b.inv_mass = shaped.inv_mass;
                b.inertia = shaped.inertia;
                b.inv_inertia = shaped.inv_inertia;
                b.radius = shaped.radius;
                b.shape = static_cast<uint32_t>(placed_shapes.size());
                placed_shapes.push_back(*rock);
            }
        }
        int cx, cy;
        cell_of(b.position, cx, cy);
        cells[static_cast<size_t>(cy) * nx + cx].push_back(static_cast<uint32_t>(placed.size()));
        placed.push_back(b);
    }
    // Rocks are created first and in order, so appending keeps bodies_ sorted by id.
    for (body& b : placed) {
        b.id = next_id_++;
        if (b.shape != no_shape) {
            const shape s = placed_shapes[b.shape];
            b.shape = static_cast<uint32_t>(shapes_.size());
            shapes_.push_back(s);
        }
        bodies_.push_back(b);
    }
    statics_dirty_ = true;
}

// An arcade rock: `polygon_vertices` corners at evenly spaced angles, each at a distance drawn
// in [0.6, 1]·radius, so that it fits in the radius the spawn checked. One draw per corner, in
// order; the hull of the corners (a dent would make it concave), centred on its centroid.
std::optional<shape> world::irregular_polygon(real radius) {
    const uint32_t n = std::min<uint32_t>(config_.rocks.polygon_vertices, max_polygon_vertices);
    std::vector<vec2> corners;
    for (uint32_t k = 0; k < n; ++k) {
        const real distance = radius * rng_.uniform(0.6f, 1.0f);
        const cos_sin at = compute_cos_sin(2 * pi * static_cast<real>(k) / static_cast<real>(n));
        corners.push_back(vec2{at.c, at.s} * distance);
    }
    const result<centred_shape> made = make_polygon(corners);
    if (!made) return std::nullopt;
    return made.value.geometry;
}

template <class IsFree>
vec2 world::random_free_position(real radius, IsFree is_free) {
    const vec2 lo{radius, radius};
    const vec2 hi = (config_.size - lo).cwiseMax(lo);
    vec2 p{0, 0};
    for (int attempt = 0; attempt < 32; ++attempt) {
        const real x = rng_.uniform(lo.x(), hi.x());
        const real y = rng_.uniform(lo.y(), hi.y());
        p = {x, y};
        if (is_free(p, radius)) break;
    }
    return p;
}

}  // namespace arena::world
