#pragma once
// The 2D cross products the contact solvers (solver.hpp, soft_solver.hpp) share.
#include "server/world/types.hpp"

namespace arena::world {

// a × b, the z of the 3D cross product: the lever arm of a force b applied at a.
inline real cross(const vec2& a, const vec2& b) {
    return a.x() * b.y() - a.y() * b.x();
}

// ω × r for a scalar ω: the velocity of a point at r on a body turning at ω.
inline vec2 cross(real w, const vec2& r) {
    return {-w * r.y(), w * r.x()};
}

// The tangent of a contact: the normal turned clockwise.
inline vec2 tangent_of(const vec2& n) {
    return {n.y(), -n.x()};
}

}  // namespace arena::world
