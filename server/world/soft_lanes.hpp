#pragma once
// The sub-stepped solver's contacts in rows of wide_lanes (wide.hpp): one lane per contact of a
// group that contact_colouring laid out, each field a `wide` so that a pass over a group is a
// handful of vector operations per point instead of one contact after another.
//
// A group is loaded from the contacts once per step (load_group), which computes the points'
// lever arms and effective masses lane by lane; the sub-steps then work on the groups alone,
// and the impulses go back to the contacts once at the end (store_group) for warm starting and
// the events. An empty lane (contact_colouring::no_contact) or a contact's missing second point
// is all zeros: no mass, no impulse, so solving it moves nothing, and its bodies are slot 0
// (static).
#include <cstdint>
#include <cstring>
#include <span>

#include "server/world/contacts.hpp"
#include "server/world/solver_slots.hpp"
#include "server/world/wide.hpp"

namespace arena::world {

struct point_lanes {
    wide separation;                       // m, at detection
    wide rn_a, rn_b, rt_a, rt_b;           // m, lever arms anchor × n and × t
    wide normal_mass, tangent_mass;        // kg
    wide normal_impulse, tangent_impulse;  // N·s, accumulated
    wide step_impulse;                     // N·s, the normal impulse over the step
};

// 400 bytes with four lanes: every pass streams the groups, so what only one pass reads lives
// elsewhere (bounce_lanes).
struct contact_lanes {
    uint32_t slot_a[wide_lanes];
    uint32_t slot_b[wide_lanes];
    wide nx, ny;  // the unit normal, a towards b
    wide friction;
    point_lanes points[2];
};

// What only the restitution pass after the sub-steps reads, apart from what every pass streams.
struct bounce_lanes {
    wide restitution;
    wide approach[2];  // m/s, each point's relative normal velocity at the step's start
};

// One side's bodies of a group: velocities, masses, and how far each moved and turned since
// detection. The masses come with the rows the velocities are in (they are not kept in the
// group: a smaller group is less to stream per pass).
struct body_lanes {
    wide vx, vy, w, inv_mass;
    wide inv_inertia, dpx, dpy, da;
};

// A body slot is two rows of four: (v.x, v.y, w, inv_mass) and (inv_inertia, dp.x, dp.y, da).
// Four slots' rows loaded whole and transposed (shuffles move bits, they compute nothing) are
// the lanes, in fewer instructions than element by element.
static_assert(wide_lanes == 4 && sizeof(body_slot) == 8 * sizeof(real), "the transposes are 4 × 4");

namespace detail {
inline wide load_row(const body_slot& s, size_t row) {
    wide r;
    std::memcpy(&r, reinterpret_cast<const real*>(&s) + 4 * row, sizeof r);
    return r;
}
inline void store_row(body_slot& s, wide r) {
    std::memcpy(reinterpret_cast<real*>(&s), &r, sizeof r);
}
// Rows r0..r3 → columns c0..c3 (c_j lane i = r_i lane j).
inline void transpose(wide r0, wide r1, wide r2, wide r3, wide& c0, wide& c1, wide& c2, wide& c3) {
    const wide t0 = __builtin_shufflevector(r0, r1, 0, 4, 1, 5);
    const wide t1 = __builtin_shufflevector(r2, r3, 0, 4, 1, 5);
    const wide t2 = __builtin_shufflevector(r0, r1, 2, 6, 3, 7);
    const wide t3 = __builtin_shufflevector(r2, r3, 2, 6, 3, 7);
    c0 = __builtin_shufflevector(t0, t1, 0, 1, 4, 5);
    c1 = __builtin_shufflevector(t0, t1, 2, 3, 6, 7);
    c2 = __builtin_shufflevector(t2, t3, 0, 1, 4, 5);
    c3 = __builtin_shufflevector(t2, t3, 2, 3, 6, 7);
}
}  // namespace detail

inline body_lanes gather_bodies(const solver_slots& slots, const uint32_t (&slot)[wide_lanes]) {
    const body_slot &s0 = slots[slot[0]], &s1 = slots[slot[1]], &s2 = slots[slot[2]], &s3 = slots[slot[3]];
    body_lanes b;
    detail::transpose(detail::load_row(s0, 0), detail::load_row(s1, 0), detail::load_row(s2, 0),
                      detail::load_row(s3, 0), b.vx, b.vy, b.w, b.inv_mass);
    detail::transpose(detail::load_row(s0, 1), detail::load_row(s1, 1), detail::load_row(s2, 1),
                      detail::load_row(s3, 1), b.inv_inertia, b.dpx, b.dpy, b.da);
    return b;
}

// The velocities back. Several empty lanes may name slot 0: they all write its zeros back
// unchanged (no mass, so no impulse moved it).
inline void scatter_velocities(solver_slots& slots, const uint32_t (&slot)[wide_lanes], const body_lanes& b) {
    wide r0, r1, r2, r3;
    detail::transpose(b.vx, b.vy, b.w, b.inv_mass, r0, r1, r2, r3);
    detail::store_row(slots[slot[0]], r0);
    detail::store_row(slots[slot[1]], r1);
    detail::store_row(slots[slot[2]], r2);
    detail::store_row(slots[slot[3]], r3);
}

// Group `lanes` (wide_lanes contact indices) of `contacts` as rows, at the step's start: the
// points' impulses of the previous step (the warm start), lever arms and effective masses (the
// anchors are fixed at detection for the whole step), the relative normal velocity before the
// step's forces (which restitution reflects, in `bounce`), no impulse yet for the step.
void load_group(contact_lanes& group, bounce_lanes& bounce, std::span<const uint32_t> lanes,
                std::span<const contact> contacts, const solver_slots& slots);
// The rows' impulses (normal, tangent, the step's) back into the contacts they came from.
void store_group(const contact_lanes& group, std::span<const uint32_t> lanes, std::span<contact> contacts);

}  // namespace arena::world
