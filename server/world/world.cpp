#include "server/world/world.hpp"

#include <algorithm>

#include "server/world/assert.hpp"
#include "server/world/forces.hpp"
#include "server/world/hash.hpp"
#include "server/world/integrate.hpp"
#include "server/world/spawn_grid.hpp"
#include "server/world/trig.hpp"

namespace arena::world {

namespace {

bool less_by_id(const body& b, uint32_t id) {
    return b.id < id;
}

}  // namespace

world::world(const world_config& config, uint64_t seed) : config_(config), rng_(seed) {
    place_bodies();
    spawn_rocks();
}

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
        std::string error;
        vec2 centre{0, 0};
        const std::optional<shape> s = make_shape(bc.shape, error, centre);
        if (!s) continue;
        body_material material = bc.material;
        const bool is_static = bc.is_static || bc.shape.type == shape_type::segment;
        if (is_static) {
            material.density = 0;
            material.mass = 0;
        }
        const cos_sin r = compute_cos_sin(bc.angle);
        const vec2 at = bc.position + vec2{r.c * centre.x() - r.s * centre.y(), r.s * centre.x() + r.c * centre.y()};
        body b = make_body(material, *s, at);
        b.angle = wrap_angle(bc.angle);
        if (!is_static) b.velocity = bc.velocity;
        if (!add_body(b, *s)) return;
    }
}

void world::step(const tick_inputs& inputs) {
    // The broadphase's lap is taken inside detection, once the bodies are bucketed.
    phase_laps laps(timer_, profile_);
    scratch_.laps = timer_.now_ns ? &laps : nullptr;
    apply_inputs(inputs);
    laps.lap(step_phase::inputs);
    if (config_.substeps > 1)
        step_substepped(laps);
    else
        step_one_pass(laps);
    note_supported();
    laps.lap(step_phase::correction);
    laps.finish();
    scratch_.laps = nullptr;
    ++tick_;
}

// Velocities, detection, one solve, positions, then a position correction.
void world::step_one_pass(phase_laps& laps) {
    const body_extent extent = integrate_velocities();
    laps.lap(step_phase::forces_velocities);
    detect_collisions(extent);
    laps.lap(step_phase::narrow_phase);
    impulses_.load(bodies_, contacts_);
    if (events_on_) events_.measure_approach(bodies_, contacts_);
    solver_.solve_velocities(bodies_, contacts_, config_);
    if (events_on_) events_.collect(bodies_, contacts_);
    impulses_.store(bodies_, contacts_);
    laps.lap(step_phase::solver);
    integrate_positions();
    laps.lap(step_phase::positions);
    solver_.correct_positions(bodies_, contacts_, config_);
    wrap_touched_bodies();
}

// Box2D v3's soft step: forces, detection, then the sub-steps (soft_solver.hpp), which integrate
// velocities and positions themselves; accumulators cleared and every body wrapped after them.
void world::step_substepped(phase_laps& laps) {
    const body_extent extent = accumulate_all_forces();
    laps.lap(step_phase::forces_velocities);
    detect_collisions(extent);
    laps.lap(step_phase::narrow_phase);
    impulses_.load(bodies_, contacts_);
    if (events_on_) events_.measure_approach(bodies_, contacts_);
    soft_solver_.step(bodies_, contacts_, config_);
    if (events_on_) events_.collect(bodies_, contacts_, true);
    impulses_.store(bodies_, contacts_);
    laps.lap(step_phase::solver);
    for (body& b : bodies_) {
        clear_accumulators(b);
        wrap_position(b, config_);
    }
    laps.lap(step_phase::positions);
}

void world::apply_inputs(const tick_inputs& inputs) {
    // In body id order, whatever order the caller listed them in.
    std::vector<const body_input*> ordered;
    ordered.reserve(inputs.size());
    for (const body_input& in : inputs) ordered.push_back(&in);
    std::stable_sort(ordered.begin(), ordered.end(),
                     [](const body_input* l, const body_input* r) { return l->body_id < r->body_id; });
    for (const body_input* in : ordered) {
        body* b = find(in->body_id);
        if (!b) continue;
        // Non-finite inputs are refused where they enter: admission for the network, the
        // replay reader for files. Clamped here, a NaN would stay NaN and spread.
        ARENA_ASSERT(!check_input(in->input), "an input reached the world without passing check_input");
        apply_player_input(*b, clamp_input(in->input), config_.control, on_ground(*b));
    }
}

// Forces and velocities in one pass: a body's forces depend only on that body, so fusing the
// phases changes no result, and the body array is streamed once instead of three times.
// The same pass gathers the extent the broadphase's grid needs (positions do not change again
// before detection).
body_extent world::integrate_velocities() {
    const real dt = config_.dt;
    body_extent extent;
    for (body& b : bodies_) {
        accumulate_forces(b, config_);
        if (config_.integrator == integrator::explicit_euler) integrate_position(b, dt);  // old velocity
        integrate_velocity(b, dt);
        if (!b.is_static()) extent.add(b);
    }
    return extent;
}

body_extent world::accumulate_all_forces() {
    body_extent extent;
    for (body& b : bodies_) {
        accumulate_forces(b, config_);
        if (!b.is_static()) extent.add(b);
    }
    return extent;
}

void world::detect_collisions(const body_extent& extent) {
    if (statics_dirty_) {
        statics_.build(bodies_, shapes_, config_);
        statics_dirty_ = false;
    }
    detect_contacts({bodies_, shapes_, &statics_}, make_grid(extent, bodies_.size(), config_), config_, scratch_,
                    query_scratch_, contacts_);
    if (config_.boundary != boundary::wrap) return;
    // Bodies in a contact may still be pushed by correct_penetration: they wrap after it.
    touched_.assign(bodies_.size(), 0);
    for (const contact& c : contacts_) {
        touched_[c.a] = 1;
        if (c.with == wall::none) touched_[c.b] = 1;
    }
}

// Positions (semi-implicit Euler, with the velocity after the contacts), accumulators cleared
// and, for bodies in no contact, wrapping, in one pass. Each is per body and a body in no
// contact is not moved again this step, so the results are those of separate passes.
void world::integrate_positions() {
    const real dt = config_.dt;
    const bool semi_implicit = config_.integrator == integrator::semi_implicit;
    const bool wraps = config_.boundary == boundary::wrap;
    for (size_t i = 0; i < bodies_.size(); ++i) {
        body& b = bodies_[i];
        if (semi_implicit) integrate_position(b, dt);
        clear_accumulators(b);
        if (wraps && !touched_[i]) wrap_position(b, config_);
    }
}

// The bodies that correct_penetration may have moved, wrapped after it (wrapping is idempotent,
// so a body in several contacts is wrapped once in effect).
void world::wrap_touched_bodies() {
    if (config_.boundary != boundary::wrap) return;
    for (const contact& c : contacts_) {
        wrap_position(bodies_[c.a], config_);
        if (c.with == wall::none) wrap_position(bodies_[c.b], config_);
    }
}

void world::set_contact_events(bool on) {
    if (on == events_on_) return;
    events_on_ = on;
    events_.reset();
}

bool world::on_ground(const body& b) const {
    return touches_floor(b, config_) || std::binary_search(supported_.begin(), supported_.end(), b.id);
}

// A body stands on what it touches below it: a contact whose normal points down from it by more
// than 45° (cos 45° ≈ 0.707), at most the slop apart. Only bodies with an owner are listed:
// jumping needs it, nothing else does.
void world::note_supported() {
    supported_.clear();
    const real down = -0.70710678f;
    for (const contact& c : contacts_) {
        if (c.separation > config_.penetration_slop) continue;
        if (c.normal.y() < down && bodies_[c.a].owner != 0) supported_.push_back(bodies_[c.a].id);
        if (c.with == wall::none && -c.normal.y() < down && bodies_[c.b].owner != 0)
            supported_.push_back(bodies_[c.b].id);
    }
    // Ids are integers: sorting them is a total order.
    std::sort(supported_.begin(), supported_.end());
}

shape world::shape_of(const body& b) const {
    return b.shape == no_shape ? make_circle(b.radius) : shapes_[b.shape];
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
    return make_polygon(corners).polygon;
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

uint64_t world::hash() const {
    fnv1a h;
    h.add_u32(tick_);
    h.add_u64(rng_.state());
    h.add_u32(static_cast<uint32_t>(bodies_.size()));
    for (const body& b : bodies_) {
        h.add_u32(b.id);
        h.add_u32(b.owner);
        h.add_real(b.mass);
        h.add_real(b.inv_mass);
        h.add_real(b.inertia);
        h.add_real(b.inv_inertia);
        h.add_real(b.radius);
        h.add_real(b.restitution);
        h.add_real(b.friction);
        h.add_u8(static_cast<uint8_t>(b.shape == no_shape ? shape_kind::circle : shapes_[b.shape].kind));
        h.add_real(b.drag_area);
        h.add_vec2(b.position);
        h.add_vec2(b.velocity);
        h.add_real(b.angle);
        h.add_real(b.angular_velocity);
        h.add_u32(b.impulse_cooldown);
        // Only a filter someone set: a world that never sets one keeps the hashes it had
        // before filters existed (the golden hashes), and one that does still hashes them all.
        if (!b.filter.is_default()) {
            h.add_u8(0xf1);
            h.add_u32(b.filter.category);
            h.add_u32(b.filter.mask);
            h.add_u32(static_cast<uint32_t>(b.filter.group));
        }
    }
    return h.value();
}

}  // namespace arena::world
