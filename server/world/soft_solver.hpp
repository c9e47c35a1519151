#pragma once
// The sub-stepped contact solver (world_config::substeps > 1): Box2D v3's "soft step" design
// (Erin Catto, "Solver2D", 2024) in our own code. Contacts are found once per step; the step's
// Δt is then cut into N sub-steps of h = Δt/N, each of which
//   1. adds the forces' share of velocity (computed once per step) to every body,
//   2. warm starts with every point's accumulated impulse,
//   3. solves each contact twice, softly: a point that overlaps is pushed apart like a damped
//      spring (see softness in soft_solver.cpp), a gap may close at most to zero within the
//      sub-step (speculative contact),
//   4. moves the bodies by h·v,
//   5. relaxes: solves each contact once more without the push, so that the push moves the
//      bodies but does not stay in their velocities.
// A point's current separation is its separation at detection plus how its two bodies moved
// and turned since (to first order in the angle), from anchors fixed at detection. After the
// sub-steps one restitution pass makes fast impacts bounce.
//
// Cheaper than the one-step solver for tall stacks: one collision pass and 3·N contact passes
// per step instead of N steps of detection, 8 velocity and 3 position passes each, and the
// sub-steps keep the stack stiff where more iterations of one big step would not.
//
// Two departures from Box2D v3's defaults (one solve pass; 30 Hz between moving bodies, 60 Hz
// against static ones), measured on the 100-level pyramid in 4 sub-steps (bench/README.md):
// with them its top sank 0.9 m and slid 0.9 m sideways in 500 steps (a spring carries the
// weight of the boxes above it, so its overlap grows with the load: about 50 boxes on the
// bottom ones); a stiffer spring alone made it shear apart (metres), a second solve pass alone
// stopped the shear but not the sinking. Both together: 0.2 m down, 2 cm sideways.
//
// Like solver.hpp it works on 32-byte slots of the bodies in contact (solver_slots.hpp); bodies
// in no contact are integrated in the same sub-steps on their own. Unlike it, the contacts are
// coloured (contact_colouring.hpp) and solved wide_lanes at a time (soft_lanes.hpp): the
// passes go colour by colour, so a contact sees the impulses of the colours before it in the
// same pass, as Box2D v3's solver does.
#include <cstdint>
#include <span>
#include <vector>

#include "server/world/body.hpp"
#include "server/world/config.hpp"
#include "server/world/contact_colouring.hpp"
#include "server/world/contacts.hpp"
#include "server/world/integrate.hpp"
#include "server/world/soft_lanes.hpp"
#include "server/world/solver_slots.hpp"

namespace arena::world {

class soft_contact_solver {
public:
    // One step of config.dt in config.substeps sub-steps, from the forces accumulated in the
    // bodies and the contacts' impulses of the previous step (impulse_cache::load). Writes every
    // moving body's velocity, position and angle, and each contact point's impulses: the last
    // sub-step's (the next step's warm start) and step_impulse (their sum over the step).
    void step(std::span<body> bodies, std::span<contact> contacts, const world_config& config);

    // A soft constraint as a velocity bias and two scales (Box2D v3's b2Softness).
    struct softness {
        real bias_rate = 0;      // 1/s, velocity bias per metre of overlap
        real mass_scale = 1;     // share of the effective mass the solve applies
        real impulse_scale = 0;  // share of the accumulated impulse the solve takes back
    };

private:
    void gather(std::span<body> bodies, std::span<contact> contacts, real h);
    void prepare(std::span<contact> contacts);
    void integrate_velocities();
    void integrate_positions(real h);
    void warm_start();
    template <bool Push>
    void solve(real h, const softness& soft);
    void restitution(real threshold);
    void scatter(std::span<body> bodies, std::span<contact> contacts);

    solver_slots slots_;
    std::vector<velocity_increment> increments_;  // slot → its velocity change per sub-step
    contact_colouring colouring_;
    std::vector<contact_lanes> groups_;  // the contacts in colour order, wide_lanes a group
    std::vector<bounce_lanes> bounces_;  // group g's restitution
};

}  // namespace arena::world
