#include "server/world/soft_lanes.hpp"

#include "server/world/contact_colouring.hpp"

namespace arena::world {

namespace {

// (x, y) × (dx, dy): the lever arm of a point at anchor (x, y) along the direction d.
inline wide cross(wide x, wide y, wide dx, wide dy) {
    return x * dy - y * dx;
}

// 1 / (the effective inverse mass along d at a point with lever arms arm_a, arm_b); 0 where
// nothing can move (no mass on either side, or an empty lane).
inline wide effective_mass(const body_lanes& a, const body_lanes& b, wide arm_a, wide arm_b) {
    const wide k = a.inv_mass + b.inv_mass + a.inv_inertia * arm_a * arm_a + b.inv_inertia * arm_b * arm_b;
    const wide zero = splat(0.0f);
    return select(k > zero, splat(1.0f) / k, zero);
}

}  // namespace

void load_group(contact_lanes& g, bounce_lanes& bounce, std::span<const uint32_t> lanes,
                std::span<const contact> contacts, const solver_slots& slots) {
    static const contact none{};  // an empty lane: no points, slot 0 on both sides
    const contact* c[wide_lanes];
    for (size_t i = 0; i < wide_lanes; ++i) {
        c[i] = lanes[i] == contact_colouring::no_contact ? &none : &contacts[lanes[i]];
        g.slot_a[i] = c[i]->slot_a;
        g.slot_b[i] = c[i]->slot_b;
    }
    g.nx = wide_of([&](size_t i) { return c[i]->normal.x(); });
    g.ny = wide_of([&](size_t i) { return c[i]->normal.y(); });
    g.friction = wide_of([&](size_t i) { return c[i]->friction; });
    bounce.restitution = wide_of([&](size_t i) { return c[i]->restitution; });
    const body_lanes a = gather_bodies(slots, g.slot_a);
    const body_lanes b = gather_bodies(slots, g.slot_b);
    const wide tx = g.ny, ty = -g.nx;
    const wide zero = splat(0.0f);
    for (int k = 0; k < 2; ++k) {
        // A contact's missing second point, like an empty lane, is all zeros.
        const wide_mask present = mask_of([&](size_t i) { return k < c[i]->count; });
        const auto field = [&](auto of) {
            return select(present, wide_of([&](size_t i) { return of(c[i]->points[k]); }), zero);
        };
        point_lanes& p = g.points[k];
        const wide anchor_ax = field([](const contact_point& q) { return q.anchor_a.x(); });
        const wide anchor_ay = field([](const contact_point& q) { return q.anchor_a.y(); });
        const wide anchor_bx = field([](const contact_point& q) { return q.anchor_b.x(); });
        const wide anchor_by = field([](const contact_point& q) { return q.anchor_b.y(); });
        p.separation = field([](const contact_point& q) { return q.separation; });
        p.normal_impulse = field([](const contact_point& q) { return q.normal_impulse; });
        p.tangent_impulse = field([](const contact_point& q) { return q.tangent_impulse; });
        p.rn_a = cross(anchor_ax, anchor_ay, g.nx, g.ny);
        p.rn_b = cross(anchor_bx, anchor_by, g.nx, g.ny);
        p.rt_a = cross(anchor_ax, anchor_ay, tx, ty);
        p.rt_b = cross(anchor_bx, anchor_by, tx, ty);
        p.normal_mass = select(present, effective_mass(a, b, p.rn_a, p.rn_b), zero);
        p.tangent_mass = select(present, effective_mass(a, b, p.rt_a, p.rt_b), zero);
        // vb + ωb × rb − va − ωa × ra, along n (ω × r = (−ω·r.y, ω·r.x)).
        const wide dvx = b.vx + -b.w * anchor_by - a.vx - -a.w * anchor_ay;
        const wide dvy = b.vy + b.w * anchor_bx - a.vy - a.w * anchor_ax;
        bounce.approach[k] = dvx * g.nx + dvy * g.ny;
        p.step_impulse = zero;
    }
}

void store_group(const contact_lanes& g, std::span<const uint32_t> lanes, std::span<contact> contacts) {
    for (size_t i = 0; i < wide_lanes; ++i) {
        if (lanes[i] == contact_colouring::no_contact) continue;
        contact& c = contacts[lanes[i]];
        for (int k = 0; k < c.count; ++k) {
            const point_lanes& p = g.points[k];
            c.points[k].normal_impulse = p.normal_impulse[i];
            c.points[k].tangent_impulse = p.tangent_impulse[i];
            c.points[k].step_impulse = p.step_impulse[i];
        }
    }
}

}  // namespace arena::world
