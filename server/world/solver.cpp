#include "server/world/solver.hpp"

#include <algorithm>
#include <cmath>

#include "server/world/trig.hpp"

namespace arena::world {

void contact_solver::solve_velocities(std::span<body> bodies, std::span<contact> contacts, const world_config& config) {
    slots_.gather(bodies, contacts);
    const real dt = config.dt;
    // A fast approach that reaches contact within this step bounces; otherwise a gap may close
    // (speculative contact: approach at most separation/Δt) and an overlap may not grow.
    const auto set_bounce = [&](const contact& c, contact_point& p, const body_slot& a, const body_slot& b,
                                const vec2& n) {
        const real vn = normal_velocity(p, a, b, n);
        const bool hits_this_step = p.separation + vn * dt < 0;
        if (vn < -config.restitution_threshold && hits_this_step) {
            p.bounce = -c.restitution * vn;
        } else {
            p.bounce = p.separation > 0 ? -p.separation / dt : 0.0f;
        }
    };
    prepare_points(contacts, slots_, set_bounce);
    // Warm start: last step's impulses at the same features are the best first guess, so that
    // stacks converge in a few iterations instead of sinking.
    for (const contact& c : contacts) apply_accumulated(c, slots_[c.slot_a], slots_[c.slot_b]);
    for (uint32_t iteration = 0; iteration < config.velocity_iterations; ++iteration) {
        for (contact& c : contacts) {
            body_slot& sa = slots_[c.slot_a];
            body_slot& sb = slots_[c.slot_b];
            contact_pair pair(sa, sb);
            const vec2 n = c.normal, t = tangent_of(n);
            // Friction first, within the cone of the current normal impulse; then the normal,
            // which matters more and so has the last word. The lever arms r × d are computed
            // once per step.
            if (c.friction > 0) solve_friction(c, pair, t);
            for (int k = 0; k < c.count; ++k) {
                contact_point& p = c.points[k];
                const real vn = pair.relative(n, p.rn_a, p.rn_b);
                const real total = std::max(p.normal_impulse + p.normal_mass * (p.bounce - vn), 0.0f);
                const real lambda = total - p.normal_impulse;
                p.normal_impulse = total;
                pair.apply(n, lambda, p.rn_a, p.rn_b);
            }
            pair.store(sa, sb);
        }
    }
    for (size_t s = 1; s < slots_.size(); ++s) {
        body& b = bodies[slots_.body_of(s)];
        b.velocity = slots_[s].v;
        b.angular_velocity = slots_[s].w;
    }
}

void contact_solver::correct_positions(std::span<body> bodies, std::span<const contact> contacts,
                                       const world_config& config) {
    // How far each slot moved and turned since detection: the integration (semi-implicit Euler
    // moved it by its new velocity; explicit Euler had moved it before detection), then the
    // corrections so far.
    const real step = config.integrator == integrator::semi_implicit ? config.dt : 0.0f;
    for (uint32_t iteration = 0; iteration < config.position_iterations; ++iteration) {
        for (const contact& c : contacts) {
            body_slot& a = slots_[c.slot_a];
            body_slot& b = slots_[c.slot_b];
            const vec2 move_a = a.v * step + a.dp, move_b = b.v * step + b.dp;
            const real turn_a = a.w * step + a.da, turn_b = b.w * step + b.da;
            for (int k = 0; k < c.count; ++k) {
                const contact_point& p = c.points[k];
                const vec2 shift = move_b + cross(turn_b, p.anchor_b) - move_a - cross(turn_a, p.anchor_a);
                const real separation = p.separation + shift.dot(c.normal);
                if (separation >= -config.penetration_slop) continue;
                const real push = std::min(config.correction_fraction * (-separation - config.penetration_slop),
                                           config.max_correction);
                const vec2 impulse = c.normal * (push * p.normal_mass);
                a.dp -= impulse * a.inv_mass;
                a.da -= a.inv_inertia * cross(p.anchor_a, impulse);
                b.dp += impulse * b.inv_mass;
                b.da += b.inv_inertia * cross(p.anchor_b, impulse);
            }
        }
    }
    for (size_t s = 1; s < slots_.size(); ++s) {
        body& b = bodies[slots_.body_of(s)];
        b.position += slots_[s].dp;
        if (slots_[s].da != 0) b.angle = wrap_angle(b.angle + slots_[s].da);
    }
    slots_.release();
}

}  // namespace arena::world
