#pragma once
// Euler integration of one body over Δt: velocities from the accumulated forces, positions
// from velocities. Semi-implicit Euler runs velocities then positions; explicit Euler runs
// positions (with the old velocity) then velocities.
//
// Defined inline: the world fuses forces and velocities into one pass over the bodies, and
// positions, wrapping and clearing into another (world.cpp), so that a step streams the body
// array twice instead of five times.
//
// integrate_free_bodies runs them on a local copy of each body, stored back once. Through a
// reference into the body array each function wrote its fields back and the next one read them
// again: a velocity stored as two 4-byte halves and reloaded as one 8-byte pair cannot be
// forwarded from the store buffer, so the load waited for the stores (several such stalls a
// body). On a copy the fields stay in registers. Same operations in the same order, so the same
// bits. 100k bodies, min of 200: 1.54 → 0.98 ms, against 0.77 + 0.31 ms for the world's own two
// passes; the 1M-body pass went from 2.1–3.0× a memcpy of its bytes to 1.3–1.7× (bench/README.md).
// Those two passes measured slower with the copy (0.77 → 1.10 and 0.29–0.31 → 0.31–0.32 ms):
// neither reads back what it stored, so they keep the reference.
#include <cmath>
#include <span>

#include "server/world/body.hpp"
#include "server/world/config.hpp"
#include "server/world/trig.hpp"

namespace arena::world {

namespace detail {

// `value` after a resistance step `delta` that opposes the motion `before` it was computed from:
// the motion stops at exactly zero rather than reversing (no jitter around rest).
// Bitwise & and | instead of && and ||: the signs of velocities are random, and the branches
// those made were a third of the force-and-velocity pass. value + (−before) is value − before.
inline real resist(real value, real before, real delta) {
    const bool overshoots = ((before > 0) & (before + delta <= 0)) | ((before < 0) & (before + delta >= 0));
    return value + (overshoots ? -before : delta);
}

}  // namespace detail

// What one velocity step of Δt adds to a body: (F/m)·Δt and (τ/I)·Δt, and the resistance's
// share (friction, drag, damping), which may stop a component but never reverse it. The
// sub-stepped solver (soft_solver.hpp) computes it once per step and adds it every sub-step.
struct velocity_increment {
    vec2 dv{0, 0};         // m/s, from the forces
    real dw = 0;           // rad/s, from the torque
    vec2 resist_dv{0, 0};  // m/s, from the resistance
    real resist_dw = 0;    // rad/s, from the resistance torque
};

inline velocity_increment velocity_increment_of(const body& b, real dt) {
    return {b.force * (b.inv_mass * dt), b.torque * (b.inv_inertia * dt), b.resistance * (b.inv_mass * dt),
            b.resistance_torque * (b.inv_inertia * dt)};
}

// v += dv, ω += dw, then the resistance's share, clipped so that it never reverses the motion.
inline void add_velocity_increment(vec2& v, real& w, const velocity_increment& inc) {
    const vec2 before = v;
    v += inc.dv;
    const real omega_before = w;
    w += inc.dw;
    // No resistance (most bodies, most steps): nothing can overshoot and resist() would return
    // value + delta, so add it without the tests. Still add it, for the same bits (−0 + 0 is +0).
    if (inc.resist_dv == vec2{0, 0} && inc.resist_dw == 0) {
        v += inc.resist_dv;
        w += inc.resist_dw;
        return;
    }
    v.x() = detail::resist(v.x(), before.x(), inc.resist_dv.x());
    v.y() = detail::resist(v.y(), before.y(), inc.resist_dv.y());
    w = detail::resist(w, omega_before, inc.resist_dw);
}

// v += (F/m)·Δt and ω += (τ/I)·Δt, then the resistance (friction, drag, damping), which may
// bring a component of velocity to exactly zero but never reverse it.
inline void integrate_velocity(body& b, real dt) {
    if (b.is_static()) return;
    add_velocity_increment(b.velocity, b.angular_velocity, velocity_increment_of(b, dt));
}

// x += v·Δt and θ += ω·Δt (θ wrapped into (−π, π]).
inline void integrate_position(body& b, real dt) {
    if (b.is_static()) return;
    b.position += b.velocity * dt;
    b.angle = wrap_angle(b.angle + b.angular_velocity * dt);
}

// Wrap-around worlds: the position back into [0, size).
inline void wrap_position(body& b, const world_config& config) {
    if (config.boundary != boundary::wrap) return;
    for (int k = 0; k < 2; ++k) {
        real& x = b.position[k];
        const real size = config.size[k];
        if (x < 0 || x >= size) {
            x -= std::floor(x / size) * size;
            if (x >= size) x = 0;  // a tiny negative rounds up to size: that is 0
        }
    }
}

// The end of a body's step: accumulators cleared, the impulse cooldown counted down.
inline void clear_accumulators(body& b) {
    b.force = {0, 0};
    b.torque = 0;
    b.resistance = {0, 0};
    b.resistance_torque = 0;
    if (b.impulse_cooldown > 0) --b.impulse_cooldown;
}

// A step of bodies that touch nothing: forces, semi-implicit Euler, wrapping and clearing in
// one pass. The world's own step runs the same per-body functions with contacts in between;
// the benchmark measures this (bench/: "integration alone") against a streaming copy.
void integrate_free_bodies(std::span<body> bodies, const world_config& config);

}  // namespace arena::world
