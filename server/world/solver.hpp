#pragma once
// The contact solver: sequential impulses with warm starting (Box2D 2.4's scheme, without its
// block solver), Coulomb friction at every point, restitution and speculative contacts through
// each point's velocity target, then a few passes of positional correction.
//
// It works on a compact copy of the bodies in contact ("slots", 32 bytes each, in the order the
// contacts first name them), so that its iterations stream one small array instead of the
// whole bodies; slot 0 is the one static body every wall and static body shares.
#include <cstdint>
#include <span>
#include <vector>

#include "server/world/body.hpp"
#include "server/world/config.hpp"
#include "server/world/contacts.hpp"
#include "server/world/solver_slots.hpp"

namespace arena::world {

class contact_solver {
public:
    // Slots, masses and velocity targets, the warm start from the points' impulses (set them
    // with impulse_cache::load first), the velocity iterations; the velocities are written back.
    void solve_velocities(std::span<body> bodies, std::span<contact> contacts, const world_config& config);
    // After the positions were integrated: pushes overlapping bodies apart beyond the slop,
    // velocities untouched. Each point's separation is estimated from its anchors and how far
    // its bodies moved and turned since detection (to first order in the angle).
    void correct_positions(std::span<body> bodies, std::span<const contact> contacts, const world_config& config);

private:
    solver_slots slots_;
};

}  // namespace arena::world
