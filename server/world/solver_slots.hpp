#pragma once
// The compact copy of the bodies in contact that both contact solvers (solver.hpp, one step;
// soft_solver.hpp, sub-steps) iterate over; then the one-step solver's point masses and impulse
// rows (the sub-stepped solver has its own, four contacts at a time: soft_lanes.hpp). Inline
// where the solver's inner loops call them, so that a contact's two velocities stay in
// registers.
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "server/world/body.hpp"
#include "server/world/contacts.hpp"
#include "server/world/cross.hpp"

namespace arena::world {

// 32 bytes: the solvers stream an array of these rather than the whole bodies.
struct body_slot {
    vec2 v{0, 0};          // m/s
    real w = 0;            // rad/s
    real inv_mass = 0;     // 1/kg
    real inv_inertia = 0;  // 1/(kg·m²)
    vec2 dp{0, 0};         // m, moved since detection (by the solver's own integration or correction)
    real da = 0;           // rad, turned since detection
};

class solver_slots {
public:
    // Slot 0 stands for every static body and wall (no mass: impulses leave it at rest); the
    // moving bodies the contacts name get slots in the order the contacts first name them.
    // Sets each contact's slot_a and slot_b.
    void gather(std::span<const body> bodies, std::span<contact> contacts);
    // Forgets which body had which slot, ready for the next step's gather.
    void release();

    size_t size() const { return slots_.size(); }
    body_slot& operator[](size_t s) { return slots_[s]; }
    const body_slot& operator[](size_t s) const { return slots_[s]; }
    uint32_t body_of(size_t s) const { return body_of_[s]; }  // slot → body index (slot 0: none)
    bool has_slot(size_t index) const { return slot_of_[index] != 0; }

private:
    std::vector<body_slot> slots_;
    std::vector<uint32_t> body_of_;
    std::vector<uint32_t> slot_of_;  // body index → slot, 0 outside a step
};

// A point's lever arms r × n and r × t and its effective masses along n and t.
inline void prepare_point_masses(contact_point& p, const body_slot& a, const body_slot& b, const vec2& n,
                                 const vec2& t) {
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
}

// Every point of every contact with its effective masses and lever arms prepared, then handed
// to `then(contact, point, slot_a, slot_b, normal)`, which sets what the solver restitutes.
template <class Then>
void prepare_points(std::span<contact> contacts, const solver_slots& slots, Then&& then) {
    for (contact& c : contacts) {
        const body_slot& a = slots[c.slot_a];
        const body_slot& b = slots[c.slot_b];
        const vec2 n = c.normal, t = tangent_of(n);
        for (int k = 0; k < c.count; ++k) {
            contact_point& p = c.points[k];
            prepare_point_masses(p, a, b, n, t);
            then(c, p, a, b, n);
        }
    }
}

// The relative normal velocity at a point from its slots' velocities: negative when closing.
inline real normal_velocity(const contact_point& p, const body_slot& a, const body_slot& b, const vec2& n) {
    const vec2 dv = b.v + cross(b.w, p.anchor_b) - a.v - cross(a.w, p.anchor_a);
    return dv.dot(n);
}

// A contact's two bodies while its points are solved, in locals: the stores and reloads
// through the slots were a chain of store forwards in the solvers' inner loops.
struct contact_pair {
    vec2 va, vb;
    real wa, wb;
    real ma, mb, ia, ib;

    contact_pair(const body_slot& a, const body_slot& b)
        : va(a.v), vb(b.v), wa(a.w), wb(b.w), ma(a.inv_mass), mb(b.inv_mass), ia(a.inv_inertia), ib(b.inv_inertia) {}
    void store(body_slot& a, body_slot& b) const {
        a.v = va;
        a.w = wa;
        b.v = vb;
        b.w = wb;
    }
    // The relative velocity along a direction d at a point, (vb − va)·d + ωb·(rb × d) − ωa·(ra × d),
    // from the lever arms r × d.
    real relative(const vec2& d, real arm_a, real arm_b) const { return (vb - va).dot(d) + wb * arm_b - wa * arm_a; }
    // An impulse λ along d, pushing b and pulling a.
    void apply(const vec2& d, real lambda, real arm_a, real arm_b) {
        const vec2 impulse = d * lambda;
        va -= impulse * ma;
        wa -= ia * (arm_a * lambda);
        vb += impulse * mb;
        wb += ib * (arm_b * lambda);
    }
};

// Coulomb friction at each point, within μ × its current normal impulse.
inline void solve_friction(contact& c, contact_pair& pair, const vec2& t) {
    for (int k = 0; k < c.count; ++k) {
        contact_point& p = c.points[k];
        const real vt = pair.relative(t, p.rt_a, p.rt_b);
        const real limit = c.friction * p.normal_impulse;
        const real total = std::clamp(p.tangent_impulse - p.tangent_mass * vt, -limit, limit);
        const real lambda = total - p.tangent_impulse;
        p.tangent_impulse = total;
        pair.apply(t, lambda, p.rt_a, p.rt_b);
    }
}

// Each point's accumulated impulses applied at once (the warm start).
inline void apply_accumulated(const contact& c, body_slot& a, body_slot& b) {
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

}  // namespace arena::world
