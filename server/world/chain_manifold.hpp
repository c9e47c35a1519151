#pragma once
// The narrow phase against a chain's segment (shape::chain, world::add_chain): one-sided, and
// smooth across the chain's joints.
//
// After Box2D v3's chain segments (our own code; see its "ghost collisions" note): a segment
// knows the chain's points before and after it (ghost vertices). A body sliding along a chain
// touches the end of the next segment before it leaves the previous one; a plain segment then
// pushes it back along the chain (it catches, or hops). Here the manifold's normal is checked
// against the neighbours:
//   - at a convex joint (the chain turns away from the body), a normal beyond the neighbour's
//     face normal belongs to the neighbour: skipped;
//   - at a concave or flat joint (turning towards the body, or not at all), a normal leaning
//     towards the joint snaps to the segment's own face;
// and a circle is collided only by the segment whose region holds its centre. A body whose
// centre lies behind the segment (and behind its convex neighbours) does not collide.
#include "server/world/manifold.hpp"
#include "server/world/shape.hpp"

namespace arena::world {

// Shape a at xa against the chain's segment `segment` at xs (segment.chain.linked): the normal
// points from a to the segment, as collide(a, xa, segment, xs) gives it.
manifold collide_chain_segment(const shape& a, const transform& xa, const shape& segment, const transform& xs,
                               real speculative);

}  // namespace arena::world
