#include "server/world/solver.hpp"

#include <algorithm>
#include <cmath>

#include "server/world/trig.hpp"

namespace arena::world {

namespace {

real cross(const vec2& a, const vec2& b) {
    return a.x() * b.y() - a.y() * b.x();
}

// ω × r for a scalar ω.
vec2 cross(real w, const vec2& r) {
    return {-w * r.y(), w * r.x()};
}

// The tangent of a contact: the normal turned clockwise.
vec2 tangent_of(const vec2& n) {
    return {n.y(), -n.x()};
}

}  // namespace

void contact_solver::solve_velocities(std::span<body> bodies, std::span<contact> contacts, const world_config& config) {
    slots_.assign(1, slot{});
    body_of_.assign(1, 0);
    if (slot_of_.size() < bodies.size()) slot_of_.resize(bodies.size(), 0);
    auto slot_for = [&](uint32_t index) -> uint32_t {
        const body& b = bodies[index];
        if (b.is_static()) return 0;
        uint32_t& s = slot_of_[index];
        if (s == 0) {
            s = static_cast<uint32_t>(slots_.size());
            slots_.push_back({b.velocity, b.angular_velocity, b.inv_mass, b.inv_inertia, {0, 0}, 0});
            body_of_.push_back(index);
        }
        return s;
    };
    const real dt = config.dt;
    for (contact& c : contacts) {
        c.slot_a = slot_for(c.a);
        c.slot_b = c.with == wall::none ? slot_for(c.b) : 0;
        const slot& a = slots_[c.slot_a];
        const slot& b = slots_[c.slot_b];
        const vec2 n = c.normal, t = tangent_of(n);
        for (int k = 0; k < c.count; ++k) {
            contact_point& p = c.points[k];
            const real rna = cross(p.anchor_a, n), rnb = cross(p.anchor_b, n);
            p.rn_a = rna;
            p.rn_b = rnb;
            const real kn = a.inv_mass + b.inv_mass + a.inv_inertia * rna * rna + b.inv_inertia * rnb * rnb;
            p.normal_mass = kn > 0 ? 1.0f / kn : 0.0f;
            const real rta = cross(p.anchor_a, t), rtb = cross(p.anchor_b, t);
            p.rt_a = rta;
            p.rt_b = rtb;
            const real kt = a.inv_mass + b.inv_mass + a.inv_inertia * rta * rta + b.inv_inertia * rtb * rtb;
            p.tangent_mass = kt > 0 ? 1.0f / kt : 0.0f;
            const vec2 dv = b.v + cross(b.w, p.anchor_b) - a.v - cross(a.w, p.anchor_a);
            const real vn = dv.dot(n);
            // A fast approach that reaches contact within this step bounces; otherwise a gap may
            // close (speculative contact: approach at most separation/Δt) and an overlap may not grow.
            const bool hits_this_step = p.separation + vn * dt < 0;
            if (vn < -config.restitution_threshold && hits_this_step) {
                p.bounce = -c.restitution * vn;
            } else {
                p.bounce = p.separation > 0 ? -p.separation / dt : 0.0f;
            }
        }
    }
    // Warm start: last step's impulses at the same features are the best first guess, so that
    // stacks converge in a few iterations instead of sinking.
    for (const contact& c : contacts) {
        slot& a = slots_[c.slot_a];
        slot& b = slots_[c.slot_b];
        const vec2 n = c.normal, t = tangent_of(n);
        for (int k = 0; k < c.count; ++k) {
            const contact_point& p = c.points[k];
            if (p.normal_impulse == 0 && p.tangent_impulse == 0) continue;
            const vec2 impulse = n * p.normal_impulse + t * p.tangent_impulse;
            a.v -= impulse * a.inv_mass;
            a.w -= a.inv_inertia * cross(p.anchor_a, impulse);
            b.v += impulse * b.inv_mass;
            b.w += b.inv_inertia * cross(p.anchor_b, impulse);
        }
    }
    for (uint32_t iteration = 0; iteration < config.velocity_iterations; ++iteration) {
        for (contact& c : contacts) {
            // The two slots' velocities in locals for the contact's points: the stores and reloads
            // through memory were a chain of store forwards in the solver's inner loop.
            slot& sa = slots_[c.slot_a];
            slot& sb = slots_[c.slot_b];
            vec2 va = sa.v, vb = sb.v;
            real wa = sa.w, wb = sb.w;
            const real ma = sa.inv_mass, mb = sb.inv_mass, ia = sa.inv_inertia, ib = sb.inv_inertia;
            const vec2 n = c.normal, t = tangent_of(n);
            // Friction first, within the cone of the current normal impulse; then the normal,
            // which matters more and so has the last word. The relative velocity along a
            // direction d at a point is (vb − va)·d + ωb·(rb × d) − ωa·(ra × d), with the lever
            // arms r × d computed once per step.
            if (c.friction > 0) {
                for (int k = 0; k < c.count; ++k) {
                    contact_point& p = c.points[k];
                    const real vt = (vb - va).dot(t) + wb * p.rt_b - wa * p.rt_a;
                    const real limit = c.friction * p.normal_impulse;
                    const real total = std::clamp(p.tangent_impulse - p.tangent_mass * vt, -limit, limit);
                    const real lambda = total - p.tangent_impulse;
                    p.tangent_impulse = total;
                    const vec2 impulse = t * lambda;
                    va -= impulse * ma;
                    wa -= ia * (p.rt_a * lambda);
                    vb += impulse * mb;
                    wb += ib * (p.rt_b * lambda);
                }
            }
            for (int k = 0; k < c.count; ++k) {
                contact_point& p = c.points[k];
                const real vn = (vb - va).dot(n) + wb * p.rn_b - wa * p.rn_a;
                const real total = std::max(p.normal_impulse + p.normal_mass * (p.bounce - vn), 0.0f);
                const real lambda = total - p.normal_impulse;
                p.normal_impulse = total;
                const vec2 impulse = n * lambda;
                va -= impulse * ma;
                wa -= ia * (p.rn_a * lambda);
                vb += impulse * mb;
                wb += ib * (p.rn_b * lambda);
            }
            sa.v = va;
            sa.w = wa;
            sb.v = vb;
            sb.w = wb;
        }
    }
    for (size_t s = 1; s < slots_.size(); ++s) {
        body& b = bodies[body_of_[s]];
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
            slot& a = slots_[c.slot_a];
            slot& b = slots_[c.slot_b];
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
        const uint32_t index = body_of_[s];
        slot_of_[index] = 0;  // ready for the next step
        body& b = bodies[index];
        b.position += slots_[s].dp;
        if (slots_[s].da != 0) b.angle = wrap_angle(b.angle + slots_[s].da);
    }
}

}  // namespace arena::world
