#include "server/world/integrate.hpp"

#include "server/world/trig.hpp"

namespace arena::world {

namespace {

// `value` after a resistance step `delta` that opposes the motion `before` it was computed from:
// the motion stops at exactly zero rather than reversing (no jitter around rest).
real resist(real value, real before, real delta) {
    const bool overshoots = (before > 0 && before + delta <= 0) || (before < 0 && before + delta >= 0);
    return overshoots ? value - before : value + delta;
}

}  // namespace

void integrate_velocity(body& b, real dt) {
    if (b.is_static()) return;
    const vec2 before = b.velocity;
    b.velocity += b.force * (b.inv_mass * dt);
    const vec2 delta = b.resistance * (b.inv_mass * dt);
    b.velocity.x() = resist(b.velocity.x(), before.x(), delta.x());
    b.velocity.y() = resist(b.velocity.y(), before.y(), delta.y());

    const real omega_before = b.angular_velocity;
    b.angular_velocity += b.torque * (b.inv_inertia * dt);
    b.angular_velocity = resist(b.angular_velocity, omega_before, b.resistance_torque * (b.inv_inertia * dt));
}

void integrate_position(body& b, real dt) {
    if (b.is_static()) return;
    b.position += b.velocity * dt;
    b.angle = wrap_angle(b.angle + b.angular_velocity * dt);
}

}  // namespace arena::world
