#include "server/world/soft_solver.hpp"

#include <algorithm>

#include "server/world/trig.hpp"

namespace arena::world {

namespace {

// Contacts are springs at a quarter of the sub-step rate (60 Hz in 4 sub-steps of 1/60 s): the
// stiffest the sub-steps resolve without ringing, as stiff as they can be since a spring's
// overlap grows with the load it carries. Damped ten times past critical, so an overlap is
// removed without bouncing back; pushed apart never faster than 3 m/s, so that a deep overlap
// (a spawn inside another body) separates without launching anything. Two soft passes per
// sub-step, one relax pass. (Box2D v3: 30 Hz, 60 Hz against static bodies, one soft pass; see
// soft_solver.hpp for why these differ.)
constexpr real hertz_per_substep_rate = 0.25f;
constexpr real contact_damping = 10.0f;  // damping ratio ζ, 1 = critical
constexpr real max_push_speed = 3.0f;    // m/s
constexpr int soft_passes = 2;

// The spring of `hertz` and damping ratio `zeta` as one implicit-Euler step of h (Catto's
// soft step): ω = 2π·f; bias_rate = ω / (2ζ + hω); the solve applies a share hω(2ζ + hω) /
// (1 + hω(2ζ + hω)) of the rigid impulse and takes back 1 / (1 + hω(2ζ + hω)) of the
// accumulated one. ζ > 0, so no denominator is zero.
soft_contact_solver::softness make_softness(real hertz, real zeta, real h) {
    const real omega = 2.0f * pi * hertz;
    const real a1 = 2.0f * zeta + h * omega;
    const real a2 = h * omega * a1;
    const real a3 = 1.0f / (1.0f + a2);
    return {omega / a1, a2 * a3, a3};
}

}  // namespace

void soft_contact_solver::step(std::span<body> bodies, std::span<contact> contacts, const world_config& config) {
    const uint32_t n = std::max<uint32_t>(config.substeps, 1);
    const real h = config.dt / static_cast<real>(n);
    const softness soft = make_softness(hertz_per_substep_rate / h, contact_damping, h);
    gather(bodies, contacts, h);
    prepare(contacts);
    // Bodies in no contact: the same sub-steps, each integrated on its own.
    for (size_t i = 0; i < bodies.size(); ++i) {
        body& b = bodies[i];
        if (b.is_static() || slots_.has_slot(i)) continue;
        for (uint32_t k = 0; k < n; ++k) {
            integrate_velocity(b, h);
            integrate_position(b, h);
        }
    }
    for (uint32_t k = 0; k < n; ++k) {
        integrate_velocities();
        warm_start(contacts);
        for (int pass = 0; pass < soft_passes; ++pass) solve<true>(contacts, h, soft);
        integrate_positions(h);
        solve<false>(contacts, h, soft);
    }
    restitution(contacts, config.restitution_threshold);
    scatter(bodies);
}

// The bodies in contact get slots (solver_slots.hpp), each with its velocity change per
// sub-step from the forces accumulated for this step.
void soft_contact_solver::gather(std::span<body> bodies, std::span<contact> contacts, real h) {
    slots_.gather(bodies, contacts);
    increments_.assign(slots_.size(), velocity_increment{});
    for (size_t s = 1; s < slots_.size(); ++s) increments_[s] = velocity_increment_of(bodies[slots_.body_of(s)], h);
}

// Effective masses and lever arms (anchors fixed at detection for the whole step), and each
// point's relative normal velocity before the step's forces, which restitution reflects.
void soft_contact_solver::prepare(std::span<contact> contacts) {
    prepare_points(contacts, slots_,
                   [](contact&, contact_point& p, const body_slot& a, const body_slot& b, const vec2& n) {
                       p.bounce = normal_velocity(p, a, b, n);
                       p.step_impulse = 0;
                   });
}

void soft_contact_solver::integrate_velocities() {
    for (size_t s = 1; s < slots_.size(); ++s) add_velocity_increment(slots_[s].v, slots_[s].w, increments_[s]);
}

void soft_contact_solver::integrate_positions(real h) {
    for (size_t s = 1; s < slots_.size(); ++s) {
        body_slot& b = slots_[s];
        b.dp += b.v * h;
        b.da += b.w * h;
    }
}

// Every sub-step starts from the impulses the previous one (or the previous step) ended with:
// they carry the stack's weight, so that the one solve pass only has to correct them.
void soft_contact_solver::warm_start(std::span<contact> contacts) {
    for (contact& c : contacts) {
        for (int k = 0; k < c.count; ++k) c.points[k].step_impulse += c.points[k].normal_impulse;
        apply_accumulated(c, slots_[c.slot_a], slots_[c.slot_b]);
    }
}

// One pass over the contacts: the normal first (it bounds friction), then friction. With Push,
// an overlap is pushed apart through the spring `soft`; without, the contact is only kept from
// closing (the relax pass: mass scale 1, nothing taken back). A gap may close within the
// sub-step either way: the speculative target is separation/h.
template <bool Push>
void soft_contact_solver::solve(std::span<contact> contacts, real h, const softness& soft) {
    const real inv_h = 1.0f / h;
    const real spring_rate = soft.mass_scale * soft.bias_rate;  // 1/s
    for (contact& c : contacts) {
        body_slot& sa = slots_[c.slot_a];
        body_slot& sb = slots_[c.slot_b];
        contact_pair pair(sa, sb);
        const vec2 n = c.normal;
        const vec2 moved = sb.dp - sa.dp;
        for (int k = 0; k < c.count; ++k) {
            contact_point& p = c.points[k];
            const vec2 shift = moved + cross(sb.da, p.anchor_b) - cross(sa.da, p.anchor_a);
            const real separation = p.separation + shift.dot(n);
            // Selects rather than branches: resting contacts hover about zero separation, and
            // which side a point is on is a coin toss the branch predictor lost.
            const bool gap = separation > 0;
            const real vn = pair.relative(n, p.rn_a, p.rn_b);
            real change;
            if constexpr (Push) {
                const real spring = std::max(spring_rate * separation, -max_push_speed);
                const real bias = gap ? separation * inv_h : spring;
                const real mass_scale = gap ? 1.0f : soft.mass_scale;
                const real impulse_scale = gap ? 0.0f : soft.impulse_scale;
                change = -p.normal_mass * (mass_scale * vn + bias) - impulse_scale * p.normal_impulse;
            } else {
                change = -p.normal_mass * (vn + (gap ? separation * inv_h : 0.0f));
            }
            const real total = std::max(p.normal_impulse + change, 0.0f);
            const real lambda = total - p.normal_impulse;
            p.normal_impulse = total;
            p.step_impulse += lambda;
            pair.apply(n, lambda, p.rn_a, p.rn_b);
        }
        if (c.friction > 0) solve_friction(c, pair, tangent_of(n));
        pair.store(sa, sb);
    }
}

// A point that approached faster than the threshold at the step's start and was pushed during
// it leaves at e times that speed. Points the solver never pushed (a speculative contact that
// stayed apart) are left alone.
void soft_contact_solver::restitution(std::span<contact> contacts, real threshold) {
    for (contact& c : contacts) {
        if (c.restitution == 0) continue;
        body_slot& sa = slots_[c.slot_a];
        body_slot& sb = slots_[c.slot_b];
        contact_pair pair(sa, sb);
        for (int k = 0; k < c.count; ++k) {
            contact_point& p = c.points[k];
            if (p.bounce > -threshold || p.step_impulse == 0) continue;
            const real vn = pair.relative(c.normal, p.rn_a, p.rn_b);
            const real total = std::max(p.normal_impulse - p.normal_mass * (vn + c.restitution * p.bounce), 0.0f);
            const real lambda = total - p.normal_impulse;
            p.normal_impulse = total;
            p.step_impulse += lambda;
            pair.apply(c.normal, lambda, p.rn_a, p.rn_b);
        }
        pair.store(sa, sb);
    }
}

void soft_contact_solver::scatter(std::span<body> bodies) {
    for (size_t s = 1; s < slots_.size(); ++s) {
        body& b = bodies[slots_.body_of(s)];
        b.velocity = slots_[s].v;
        b.angular_velocity = slots_[s].w;
        b.position += slots_[s].dp;
        b.angle = wrap_angle(b.angle + slots_[s].da);
    }
    slots_.release();
}

}  // namespace arena::world
