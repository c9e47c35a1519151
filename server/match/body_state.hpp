#pragma once
// A world body as the wire's BodyState: the one conversion every snapshot path uses (full
// frames, the quantised delta state, the snapshot benchmark).
#include "protocol/arena_generated.h"
#include "server/world/body.hpp"

namespace arena::match {

[[nodiscard]] inline protocol::BodyState body_state(const world::body& b) {
    return {b.id, b.owner, b.position.x(), b.position.y(), b.velocity.x(), b.velocity.y(), b.angle, b.angular_velocity};
}

}  // namespace arena::match
