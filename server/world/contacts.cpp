#include "server/world/contacts.hpp"

#include <algorithm>
#include <cmath>

#include "server/world/chain_manifold.hpp"
#include "server/world/manifold.hpp"
#include "server/world/splitmix64.hpp"

namespace arena::world {

namespace {

bool has_wall(const world_config& config, wall w) {
    if (config.boundary == boundary::walls) return true;
    return config.boundary == boundary::floor && w == wall::bottom;
}

// The wall as a half-space {x : normal·x ≥ offset}, normal pointing out of the world.
void wall_plane(wall w, const world_config& config, vec2& normal, real& offset) {
    switch (w) {
        case wall::left:
            normal = {-1, 0};
            offset = 0;
            return;
        case wall::right:
            normal = {1, 0};
            offset = config.size.x();
            return;
        case wall::bottom:
            normal = {0, -1};
            offset = 0;
            return;
        case wall::top:
        case wall::none:
            normal = {0, 1};
            offset = config.size.y();
            return;
    }
}

real mix_friction(real a, real b) {
    return std::sqrt(a * b);
}

// A contact from a manifold whose points are in the frame where a is at `pa` and b at `pb`.
contact make_contact(uint32_t a, uint32_t b, const manifold& m, const vec2& pa, const vec2& pb) {
    contact c;
    c.a = a;
    c.b = b;
    c.count = m.count;
    c.normal = m.normal;
    c.separation = m.points[0].separation;
    for (int k = 0; k < m.count; ++k) {
        contact_point& p = c.points[k];
        p.anchor_a = m.points[k].point - pa;
        p.anchor_b = m.points[k].point - pb;
        p.separation = m.points[k].separation;
        p.id = m.points[k].id;
        c.separation = std::min(c.separation, p.separation);
    }
    return c;
}

// The shape of body b: its own, or a circle of its radius.
const shape& shape_of(const body& b, std::span<const shape> pool, shape& circle) {
    if (b.shape != no_shape) return pool[b.shape];
    circle = make_circle(b.radius);
    return circle;
}

transform transform_of(const body& b, uint32_t index, const vec2& position, const broadphase_scratch& s) {
    if (b.shape == no_shape) return {position, 1, 0};
    const cos_sin r = s.rotations[index];
    return {position, r.c, r.s};
}

// Bodies ia and ib of which one at least has a shape, b at pb. Two hulls (2 to 8 vertices)
// meet through the shapes the broadphase turned; a circle through the shapes themselves. Out
// of line: inlined, it slowed the candidate loop around it, where sparse worlds spend their
// narrow phase.
__attribute__((noinline)) manifold collide_shapes(uint32_t ia, uint32_t ib, const vec2& pb,
                                                  const collision_scene& scene, const broadphase_scratch& s,
                                                  real spec) {
    const body& a = scene.bodies[ia];
    const body& b = scene.bodies[ib];
    if (a.shape != no_shape && b.shape != no_shape) {
        const turned_shape& ta = s.turned[ia];
        const turned_shape& tb = s.turned[ib];
        if (ta.count > 1 && tb.count > 1) return collide_hulls(ta, a.position, tb, pb, spec);
    }
    shape circle_a, circle_b;
    return collide(shape_of(a, scene.pool, circle_a), transform_of(a, ia, a.position, s),
                   shape_of(b, scene.pool, circle_b), transform_of(b, ib, pb, s), spec);
}

aabb box_of(const cell_proxy& p, real margin) {
    const vec2 reach = p.half + vec2{margin, margin};
    return {p.position - reach, p.position + reach};
}

}  // namespace

void detect_contacts(std::span<const body> bodies, const world_config& config, broadphase_scratch& scratch,
                     std::vector<contact>& out) {
    std::vector<uint32_t> query_scratch;
    detect_contacts({bodies, {}, nullptr}, make_grid(bodies, config), config, scratch, query_scratch, out);
}

void detect_contacts(const collision_scene& scene, const grid& g, const world_config& config,
                     broadphase_scratch& scratch, std::vector<uint32_t>& query_scratch, std::vector<contact>& out) {
    out.clear();
    const std::span<const body> bodies = scene.bodies;
    const real spec = config.speculative_distance;
    // The cheap tests read the broadphase's proxies; only a contact reads the bodies. Inlined
    // into both of the walk's loops: GCC left it a call, a tenth of a dense step.
    for_each_candidate_pair(bodies, g, scratch,
                            [&](const cell_proxy& p, const cell_proxy& q) __attribute__((always_inline)) {
                                // The tests are symmetric (negating a displacement and swapping a sum are exact), so
                                // only a contact puts the pair in index order: a choice per candidate was a
                                // mispredicted branch.
                                const vec2 d = displacement(p.position, q.position, config);
                                if (p.is_circle() && q.is_circle()) {
                                    const real reach = p.radius + q.radius + spec;
                                    if (d.squaredNorm() >= reach * reach) return;
                                } else if (std::abs(d.x()) > p.half.x() + q.half.x() + spec ||
                                           std::abs(d.y()) > p.half.y() + q.half.y() + spec) {
                                    return;
                                }
                                const bool p_first = p.index < q.index;
                                const uint32_t ia = p_first ? p.index : q.index;
                                const uint32_t ib = p_first ? q.index : p.index;
                                const body& a = bodies[ia];
                                const body& b = bodies[ib];
                                if (a.is_static() && b.is_static()) return;
                                if (!should_collide(a.filter, b.filter)) return;
                                // b where a sees it: across the seam in a wrapping world.
                                const vec2 pb = a.position + displacement(a.position, b.position, config);
                                manifold m;
                                if (p.is_circle() && q.is_circle()) {
                                    m = collide_circles(a.position, a.radius, pb, b.radius, spec);
                                } else {
                                    m = collide_shapes(ia, ib, pb, scene, scratch, spec);
                                }
                                if (m.count == 0) return;
                                contact c = make_contact(ia, ib, m, a.position, pb);
                                c.friction = mix_friction(a.friction, b.friction);
                                c.restitution = std::max(a.restitution, b.restitution);
                                out.push_back(c);
                            },
                            {scene.pool, scene.statics != nullptr});
    const bool walls = config.boundary == boundary::walls || config.boundary == boundary::floor;
    const bool statics = scene.statics && !scene.statics->empty();
    if (!walls && !statics) return;
    const bool four_walls = config.boundary == boundary::walls;
    for (uint32_t i = 0; i < bodies.size(); ++i) {
        const body& b = bodies[i];
        if (b.is_static()) continue;
        const cell_proxy& proxy = scratch.unsorted[i];
        if (statics) {
            shape circle;
            const shape* own = nullptr;
            const auto visit = [&](const static_index::entry& e, const vec2& offset) {
                if (!own) own = &shape_of(b, scene.pool, circle);
                shape other_circle;
                const body& other = bodies[e.index];
                if (!should_collide(b.filter, other.filter)) return;
                const shape& fixed = shape_of(other, scene.pool, other_circle);
                const transform xf = transform_of(b, i, b.position, scratch);
                // The static body where b meets it: across the seam in a wrapping world.
                const transform image{e.xf.p + offset, e.xf.c, e.xf.s};
                const manifold m = fixed.chain.linked ? collide_chain_segment(*own, xf, fixed, image, spec)
                                                      : collide(*own, xf, fixed, image, spec);
                if (m.count == 0) return;
                contact c = make_contact(i, e.index, m, b.position, image.p);
                c.friction = mix_friction(b.friction, other.friction);
                c.restitution = std::max(b.restitution, other.restitution);
                out.push_back(c);
            };
            scene.statics->query(box_of(proxy, spec), query_scratch, visit);
        }
        if (!walls) continue;
        // Most bodies are far from every wall: one test on the bounding box before the per-wall
        // work.
        const vec2 lo = proxy.position - proxy.half, hi = proxy.position + proxy.half;
        const bool far_from_floor = lo.y() >= spec;
        const bool far_from_left = lo.x() >= spec;
        const bool far_from_right = config.size.x() - hi.x() >= spec;
        const bool far_from_top = config.size.y() - hi.y() >= spec;
        const bool far_from_walls = !four_walls || (far_from_left & far_from_right & far_from_top);
        if (far_from_floor & far_from_walls) continue;
        shape circle;
        const shape& own = shape_of(b, scene.pool, circle);
        const transform xf = transform_of(b, i, b.position, scratch);
        for (wall w : {wall::left, wall::right, wall::bottom, wall::top}) {
            if (!has_wall(config, w)) continue;
            vec2 normal{0, 0};
            real offset = 0;
            wall_plane(w, config, normal, offset);
            const manifold m = collide_wall(own, xf, normal, offset, spec);
            if (m.count == 0) continue;
            contact c = make_contact(i, i, m, b.position, b.position);
            c.with = w;
            // The lecture's floor model (forces.hpp) already gives a circle its floor friction.
            c.friction = b.shape == no_shape ? 0.0f : mix_friction(b.friction, config.floor_friction);
            c.restitution = b.restitution;
            out.push_back(c);
        }
    }
}

namespace {

uint64_t contact_key(std::span<const body> bodies, const contact& c) {
    const uint64_t a = bodies[c.a].id;
    const uint64_t b = c.with == wall::none ? bodies[c.b].id : 0xfffffff0u + static_cast<uint32_t>(c.with);
    return a << 32 | b;
}

}  // namespace

namespace {

// The table's hash of a key: one splitmix64 step, the code base's one mixer.
uint64_t mix(uint64_t key) {
    return splitmix64(key).next();
}

}  // namespace

const impulse_cache::entry* impulse_cache::find(uint64_t key) {
    if (table_.empty()) build_table();
    const size_t mask = table_.size() - 1;
    for (size_t at = mix(key) & mask;; at = (at + 1) & mask) {
        const uint32_t k = table_[at];
        if (k == 0) return nullptr;
        if (entries_[k - 1].key == key) return &entries_[k - 1];
    }
}

// Keys are unique (one contact per pair or body and wall): each finds its own entry.
void impulse_cache::build_table() {
    size_t size = 16;
    while (size < 2 * entries_.size()) size *= 2;
    table_.assign(size, 0);
    const size_t mask = size - 1;
    for (uint32_t k = 0; k < entries_.size(); ++k) {
        size_t at = mix(entries_[k].key) & mask;
        while (table_[at] != 0) at = (at + 1) & mask;
        table_[at] = k + 1;
    }
}

// Contacts come in the broadphase's order, which changes little from one step to the next: the
// entry after the last one found is tried first, and the table is built only when that fails.
// Either way a contact gets the entry of its key, so the walk changes no result.
void impulse_cache::load(std::span<const body> bodies, std::span<contact> contacts) {
    size_t next = 0;
    for (contact& c : contacts) {
        const uint64_t key = contact_key(bodies, c);
        const entry* e = nullptr;
        if (next < entries_.size() && entries_[next].key == key) {
            e = &entries_[next];
        } else {
            e = find(key);
        }
        if (e) next = static_cast<size_t>(e - entries_.data()) + 1;
        for (int k = 0; k < c.count; ++k) {
            contact_point& p = c.points[k];
            p.normal_impulse = 0;
            p.tangent_impulse = 0;
            if (!e) continue;
            for (int j = 0; j < e->count; ++j) {
                if (e->id[j] != p.id) continue;
                p.normal_impulse = e->normal[j];
                p.tangent_impulse = e->tangent[j];
            }
        }
    }
}

// Every contact, even one without impulses: the next step's walk then finds its successor in
// place.
void impulse_cache::store(std::span<const body> bodies, std::span<const contact> contacts) {
    entries_.clear();
    for (const contact& c : contacts) {
        entry e{contact_key(bodies, c), {0, 0}, c.count, {0, 0}, {0, 0}};
        for (int k = 0; k < c.count; ++k) {
            e.id[k] = c.points[k].id;
            e.normal[k] = c.points[k].normal_impulse;
            e.tangent[k] = c.points[k].tangent_impulse;
        }
        entries_.push_back(e);
    }
    table_.clear();
}

}  // namespace arena::world
