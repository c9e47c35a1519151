#include "server/world/contacts.hpp"

#include <algorithm>
#include <cmath>

#include "server/world/integrate.hpp"

namespace arena::world {

namespace {

bool has_wall(const world_config& config, wall w) {
    if (config.boundary == boundary::walls) return true;
    return config.boundary == boundary::floor && w == wall::bottom;
}

// Distance from the body's surface to the wall (negative when crossing it), and the normal
// pointing from the body into the wall.
real wall_separation(const body& b, wall w, const world_config& config, vec2& normal) {
    switch (w) {
        case wall::left:
            normal = {-1, 0};
            return b.position.x() - b.radius;
        case wall::right:
            normal = {1, 0};
            return config.size.x() - b.position.x() - b.radius;
        case wall::bottom:
            normal = {0, -1};
            return b.position.y() - b.radius;
        case wall::top:
            normal = {0, 1};
            return config.size.y() - b.position.y() - b.radius;
        case wall::none:
            break;
    }
    return 0;
}

// Separation of two circles whose centres are `d` apart (from a to b), and the unit normal.
real pair_separation(const vec2& d, real radius_a, real radius_b, vec2& normal) {
    const real dist = std::sqrt(d.squaredNorm());
    normal = dist > 0 ? vec2{d / dist} : vec2{1, 0};  // coincident centres: any fixed axis
    return dist - radius_a - radius_b;
}

// Current separation and normal of a contact, from the bodies' positions now.
real measure(std::span<const body> bodies, const contact& c, const world_config& config, vec2& normal) {
    const body& a = bodies[c.a];
    if (c.with != wall::none) return wall_separation(a, c.with, config, normal);
    const body& b = bodies[c.b];
    return pair_separation(displacement(a.position, b.position, config), a.radius, b.radius, normal);
}

void prepare(std::span<const body> bodies, contact& c, const world_config& config) {
    const body& a = bodies[c.a];
    const bool wall_contact = c.with != wall::none;
    const real inv_b = wall_contact ? 0.0f : bodies[c.b].inv_mass;
    const real inv_sum = a.inv_mass + inv_b;
    c.effective_mass = inv_sum > 0 ? 1.0f / inv_sum : 0.0f;
    const vec2 vb = wall_contact ? vec2{0, 0} : bodies[c.b].velocity;
    const real vn = (vb - a.velocity).dot(c.normal);
    const real e = wall_contact ? a.restitution : std::max(a.restitution, bodies[c.b].restitution);
    // A fast approach that reaches contact within this step bounces; otherwise a gap may close
    // (speculative contact: approach at most separation/Δt) and an overlap may not grow.
    const bool hits_this_step = c.separation + vn * config.dt < 0;
    if (vn < -config.restitution_threshold && hits_this_step) {
        c.bounce = -e * vn;
    } else {
        c.bounce = c.separation > 0 ? -c.separation / config.dt : 0.0f;
    }
}

}  // namespace

void detect_contacts(std::span<const body> bodies, const world_config& config, broadphase_scratch& scratch,
                     std::vector<contact>& out) {
    detect_contacts(bodies, make_grid(bodies, config), config, scratch, out);
}

void detect_contacts(std::span<const body> bodies, const grid& g, const world_config& config,
                     broadphase_scratch& scratch, std::vector<contact>& out) {
    out.clear();
    // The distance test reads the broadphase's proxies; only a contact reads the bodies. Inlined
    // into both of the walk's loops: GCC left it a call, a tenth of a dense step.
    for_each_candidate_pair(
        bodies, g, scratch, [&](const cell_proxy& p, const cell_proxy& q) __attribute__((always_inline)) {
            // The test is symmetric (negating a displacement and swapping a sum are exact), so only
            // a contact puts the pair in index order: a choice per candidate was a mispredicted branch.
            const real reach = p.radius + q.radius + config.speculative_distance;
            if (displacement(p.position, q.position, config).squaredNorm() >= reach * reach) return;
            const bool p_first = p.index < q.index;
            const cell_proxy& pa = p_first ? p : q;
            const cell_proxy& pb = p_first ? q : p;
            if (bodies[pa.index].is_static() && bodies[pb.index].is_static()) return;
            contact c;
            c.a = pa.index;
            c.b = pb.index;
            c.separation =
                pair_separation(displacement(pa.position, pb.position, config), pa.radius, pb.radius, c.normal);
            prepare(bodies, c, config);
            out.push_back(c);
        });
    if (config.boundary != boundary::walls && config.boundary != boundary::floor) return;
    const bool four_walls = config.boundary == boundary::walls;
    for (uint32_t i = 0; i < bodies.size(); ++i) {
        const body& b = bodies[i];
        if (b.is_static()) continue;
        // Most bodies are far from every wall: one test on the separations wall_separation
        // gives (the same expressions) before the per-wall work.
        const real spec = config.speculative_distance;
        const bool far_from_floor = b.position.y() - b.radius >= spec;
        const bool far_from_left = b.position.x() - b.radius >= spec;
        const bool far_from_right = config.size.x() - b.position.x() - b.radius >= spec;
        const bool far_from_top = config.size.y() - b.position.y() - b.radius >= spec;
        const bool far_from_walls = !four_walls || (far_from_left & far_from_right & far_from_top);
        if (far_from_floor & far_from_walls) continue;
        for (wall w : {wall::left, wall::right, wall::bottom, wall::top}) {
            if (!has_wall(config, w)) continue;
            contact c;
            c.a = i;
            c.with = w;
            c.separation = wall_separation(bodies[i], w, config, c.normal);
            if (c.separation >= config.speculative_distance) continue;
            prepare(bodies, c, config);
            out.push_back(c);
        }
    }
}

void solve_contact_velocities(std::span<body> bodies, std::span<contact> contacts, const world_config& config) {
    // Warm start: last step's impulse of the same contact is the best first guess, so that
    // stacks converge in a few iterations instead of sinking.
    for (const contact& c : contacts) {
        if (c.impulse == 0 || c.effective_mass == 0) continue;
        const vec2 p = c.normal * c.impulse;
        bodies[c.a].velocity -= p * bodies[c.a].inv_mass;
        if (c.with == wall::none) bodies[c.b].velocity += p * bodies[c.b].inv_mass;
    }
    for (uint32_t iteration = 0; iteration < config.velocity_iterations; ++iteration) {
        for (contact& c : contacts) {
            if (c.effective_mass == 0) continue;
            body& a = bodies[c.a];
            body* b = c.with == wall::none ? &bodies[c.b] : nullptr;
            const vec2 vb = b ? b->velocity : vec2{0, 0};
            const real vn = (vb - a.velocity).dot(c.normal);
            const real total = std::max(c.impulse + c.effective_mass * (c.bounce - vn), 0.0f);
            const real delta = total - c.impulse;
            c.impulse = total;
            const vec2 p = c.normal * delta;
            a.velocity -= p * a.inv_mass;
            if (b) b->velocity += p * b->inv_mass;
        }
    }
}

void correct_penetration(std::span<body> bodies, std::span<const contact> contacts, const world_config& config) {
    for (uint32_t iteration = 0; iteration < config.position_iterations; ++iteration) {
        for (const contact& c : contacts) {
            if (c.effective_mass == 0) continue;
            vec2 normal{0, 0};
            const real separation = measure(bodies, c, config, normal);
            if (separation >= -config.penetration_slop) continue;
            const real push =
                std::min(config.correction_fraction * (-separation - config.penetration_slop), config.max_correction);
            const vec2 p = normal * (push * c.effective_mass);
            body& a = bodies[c.a];
            a.position -= p * a.inv_mass;
            if (c.with == wall::none) bodies[c.b].position += p * bodies[c.b].inv_mass;
        }
    }
}

}  // namespace arena::world

namespace arena::world {

uint64_t contact_key(std::span<const body> bodies, const contact& c) {
    const uint64_t a = bodies[c.a].id;
    const uint64_t b = c.with == wall::none ? bodies[c.b].id : 0xfffffff0u + static_cast<uint32_t>(c.with);
    return a << 32 | b;
}

void impulse_cache::load(std::span<const body> bodies, std::span<contact> contacts) const {
    for (contact& c : contacts) {
        const uint64_t key = contact_key(bodies, c);
        auto at = std::lower_bound(entries_.begin(), entries_.end(), key,
                                   [](const entry& e, uint64_t k) { return e.key < k; });
        c.impulse = (at != entries_.end() && at->key == key) ? at->impulse : 0.0f;
    }
}

void impulse_cache::store(std::span<const body> bodies, std::span<const contact> contacts) {
    entries_.clear();
    for (const contact& c : contacts)
        if (c.impulse > 0) entries_.push_back({contact_key(bodies, c), c.impulse});
    // Keys are unique (one contact per pair or body and wall), so this order is total.
    std::sort(entries_.begin(), entries_.end(), [](const entry& l, const entry& r) { return l.key < r.key; });
}

}  // namespace arena::world
