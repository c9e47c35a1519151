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
        warm_start();
        for (int pass = 0; pass < soft_passes; ++pass) solve<true>(h, soft);
        integrate_positions(h);
        solve<false>(h, soft);
    }
    restitution(config.restitution_threshold);
    scatter(bodies, contacts);
}

// The bodies in contact get slots (solver_slots.hpp), each with its velocity change per
// sub-step from the forces accumulated for this step.
void soft_contact_solver::gather(std::span<body> bodies, std::span<contact> contacts, real h) {
    slots_.gather(bodies, contacts);
    increments_.assign(slots_.size(), velocity_increment{});
    for (size_t s = 1; s < slots_.size(); ++s) increments_[s] = velocity_increment_of(bodies[slots_.body_of(s)], h);
}

// The contacts coloured and loaded into their groups (soft_lanes.hpp: lever arms, effective
// masses, the warm start's impulses).
void soft_contact_solver::prepare(std::span<contact> contacts) {
    colouring_.colour(contacts, slots_.size());
    const std::span<const uint32_t> lanes = colouring_.lanes();
    groups_.resize(colouring_.group_count());
    bounces_.resize(groups_.size());
    for (size_t g = 0; g < groups_.size(); ++g)
        load_group(groups_[g], bounces_[g], lanes.subspan(g * wide_lanes, wide_lanes), contacts, slots_);
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

namespace {

// The relative velocity along (dx, dy) at a point, (vb − va)·d + (ωb·arm_b − ωa·arm_a), from
// the lever arms r × d. Summed as two halves, linear and angular: a pass is a chain of one
// point's impulse feeding the next point's velocity, and two halves are a shorter chain than
// four terms in a row.
inline wide relative(const body_lanes& a, const body_lanes& b, wide dx, wide dy, wide arm_a, wide arm_b) {
    return ((b.vx - a.vx) * dx + (b.vy - a.vy) * dy) + (b.w * arm_b - a.w * arm_a);
}

// An impulse λ along (dx, dy), pushing b and pulling a.
inline void apply(body_lanes& a, body_lanes& b, wide dx, wide dy, wide lambda, wide arm_a, wide arm_b) {
    const wide px = dx * lambda, py = dy * lambda;
    a.vx -= px * a.inv_mass;
    a.vy -= py * a.inv_mass;
    a.w -= a.inv_inertia * (arm_a * lambda);
    b.vx += px * b.inv_mass;
    b.vy += py * b.inv_mass;
    b.w += b.inv_inertia * (arm_b * lambda);
}

// The point's separation now: at detection, plus how its two bodies moved and turned since
// along the normal, to first order in the angle: (Δpb − Δpa)·n + Δθb·(rb × n) − Δθa·(ra × n),
// since (θ × r)·n = θ·(r × n). The first term is the contact's, shared by its points.
inline wide moved_along_normal(const contact_lanes& g, const body_lanes& a, const body_lanes& b) {
    return (b.dpx - a.dpx) * g.nx + (b.dpy - a.dpy) * g.ny;
}
inline wide current_separation(const point_lanes& p, wide moved, const body_lanes& a, const body_lanes& b) {
    return p.separation + (moved + b.da * p.rn_b - a.da * p.rn_a);
}

// Coulomb friction at each point, within μ × its current normal impulse. The tangent is the
// normal turned a quarter clockwise, (ny, −nx).
inline void solve_friction(contact_lanes& g, body_lanes& a, body_lanes& b) {
    const wide tx = g.ny, ty = -g.nx;
    for (point_lanes& p : g.points) {
        const wide vt = relative(a, b, tx, ty, p.rt_a, p.rt_b);
        const wide limit = g.friction * p.normal_impulse;
        const wide total = clamp(p.tangent_impulse - p.tangent_mass * vt, -limit, limit);
        const wide lambda = total - p.tangent_impulse;
        p.tangent_impulse = total;
        apply(a, b, tx, ty, lambda, p.rt_a, p.rt_b);
    }
}

// The velocities of `after` in the lanes of `mask`, the others' bit for bit as they were.
inline void keep_unless(wide_mask mask, body_lanes& bodies, const body_lanes& after) {
    bodies.vx = select(mask, after.vx, bodies.vx);
    bodies.vy = select(mask, after.vy, bodies.vy);
    bodies.w = select(mask, after.w, bodies.w);
}

}  // namespace

// Every sub-step starts from the impulses the previous one (or the previous step) ended with:
// they carry the stack's weight, so that the solve passes only have to correct them.
void soft_contact_solver::warm_start() {
    for (contact_lanes& g : groups_) {
        body_lanes a = gather_bodies(slots_, g.slot_a);
        body_lanes b = gather_bodies(slots_, g.slot_b);
        const wide tx = g.ny, ty = -g.nx;
        for (point_lanes& p : g.points) {
            p.step_impulse += p.normal_impulse;
            const wide px = g.nx * p.normal_impulse + tx * p.tangent_impulse;
            const wide py = g.ny * p.normal_impulse + ty * p.tangent_impulse;
            a.vx -= px * a.inv_mass;
            a.vy -= py * a.inv_mass;
            a.w -= a.inv_inertia * (p.rn_a * p.normal_impulse + p.rt_a * p.tangent_impulse);
            b.vx += px * b.inv_mass;
            b.vy += py * b.inv_mass;
            b.w += b.inv_inertia * (p.rn_b * p.normal_impulse + p.rt_b * p.tangent_impulse);
        }
        scatter_velocities(slots_, g.slot_a, a);
        scatter_velocities(slots_, g.slot_b, b);
    }
}

// One pass over the groups: the normal first (it bounds friction), then friction. With Push,
// an overlap is pushed apart through the spring `soft`; without, the contact is only kept from
// closing (the relax pass: mass scale 1, nothing taken back). A gap may close within the
// sub-step either way: the speculative target is separation/h. Selects rather than branches,
// lane by lane: resting contacts hover about zero separation.
template <bool Push>
void soft_contact_solver::solve(real h, const softness& soft) {
    const wide inv_h = splat(1.0f / h);
    const wide spring_rate = splat(soft.mass_scale * soft.bias_rate);  // 1/s
    const wide zero = splat(0.0f), one = splat(1.0f);
    const wide max_push = splat(-max_push_speed);
    const wide mass_scale = splat(soft.mass_scale), impulse_scale = splat(soft.impulse_scale);
    for (contact_lanes& g : groups_) {
        body_lanes a = gather_bodies(slots_, g.slot_a);
        body_lanes b = gather_bodies(slots_, g.slot_b);
        const wide moved = moved_along_normal(g, a, b);
        for (point_lanes& p : g.points) {
            const wide separation = current_separation(p, moved, a, b);
            const wide_mask gap = separation > zero;
            const wide vn = relative(a, b, g.nx, g.ny, p.rn_a, p.rn_b);
            wide change;
            if constexpr (Push) {
                const wide spring = max(spring_rate * separation, max_push);
                const wide bias = select(gap, separation * inv_h, spring);
                const wide scale = select(gap, one, mass_scale);
                const wide take_back = select(gap, zero, impulse_scale);
                change = -p.normal_mass * (scale * vn + bias) - take_back * p.normal_impulse;
            } else {
                change = -p.normal_mass * (vn + select(gap, separation * inv_h, zero));
            }
            const wide total = max(p.normal_impulse + change, zero);
            const wide lambda = total - p.normal_impulse;
            p.normal_impulse = total;
            p.step_impulse += lambda;
            apply(a, b, g.nx, g.ny, lambda, p.rn_a, p.rn_b);
        }
        solve_friction(g, a, b);
        scatter_velocities(slots_, g.slot_a, a);
        scatter_velocities(slots_, g.slot_b, b);
    }
}

// A point that approached faster than the threshold at the step's start and was pushed during
// it leaves at e times that speed. Points the solver never pushed (a speculative contact that
// stayed apart), and contacts without restitution, are left alone: their lanes keep their
// velocities and impulses bit for bit.
void soft_contact_solver::restitution(real threshold) {
    const wide zero = splat(0.0f), slower = splat(-threshold);
    for (size_t group = 0; group < groups_.size(); ++group) {
        contact_lanes& g = groups_[group];
        const bounce_lanes& bounce = bounces_[group];
        const wide_mask bouncy = bounce.restitution != zero;
        bool any = false;
        for (size_t i = 0; i < wide_lanes; ++i) any |= bouncy[i] != 0;
        if (!any) continue;
        body_lanes a = gather_bodies(slots_, g.slot_a);
        body_lanes b = gather_bodies(slots_, g.slot_b);
        for (int k = 0; k < 2; ++k) {
            point_lanes& p = g.points[k];
            const wide approach = bounce.approach[k];
            const wide_mask bounces = bouncy & (approach <= slower) & (p.step_impulse != zero);
            const wide vn = relative(a, b, g.nx, g.ny, p.rn_a, p.rn_b);
            const wide total = max(p.normal_impulse - p.normal_mass * (vn + bounce.restitution * approach), zero);
            const wide lambda = total - p.normal_impulse;
            body_lanes a_after = a, b_after = b;
            apply(a_after, b_after, g.nx, g.ny, lambda, p.rn_a, p.rn_b);
            p.normal_impulse = select(bounces, total, p.normal_impulse);
            p.step_impulse = select(bounces, p.step_impulse + lambda, p.step_impulse);
            keep_unless(bounces, a, a_after);
            keep_unless(bounces, b, b_after);
        }
        scatter_velocities(slots_, g.slot_a, a);
        scatter_velocities(slots_, g.slot_b, b);
    }
}

void soft_contact_solver::scatter(std::span<body> bodies, std::span<contact> contacts) {
    const std::span<const uint32_t> lanes = colouring_.lanes();
    for (size_t g = 0; g < groups_.size(); ++g)
        store_group(groups_[g], lanes.subspan(g * wide_lanes, wide_lanes), contacts);
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
