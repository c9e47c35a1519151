#pragma once
// A world body's shape as the protocol describes it (protocol/shapes.hpp), and the static
// geometry a Welcome carries.
#include <vector>

#include "protocol/shapes.hpp"
#include "server/match/body_kinds.hpp"
#include "server/world/world.hpp"

namespace arena::match {

[[nodiscard]] protocol::shape_desc describe(const world::world& w, const world::body& b, uint8_t kind);

// Every static body of `w`, by increasing id, with its pose and shape.
[[nodiscard]] std::vector<protocol::static_body> static_geometry(const world::world& w, const body_kinds& kinds);

}  // namespace arena::match
