#pragma once
// Sine and cosine from + − × ÷ only, so that every compiler and libm gives the same bits
// (glibc's sinf and GCC's constant folding disagree with clang's; docs/DETERMINISM.md rule 2).
#include "server/world/types.hpp"

namespace arena::world {

inline constexpr real pi = 3.14159265358979323846f;

struct cos_sin {
    real c;
    real s;
};

// Cosine and sine of `angle` (radians, any finite value). Max error about 1e-7 over [−π, π].
cos_sin compute_cos_sin(real angle);

// `angle` wrapped into (−π, π]. Inline: every body's angle goes through it every step.
inline real wrap_angle(real angle) {
    const real two_pi = 2.0f * pi;
    if (angle > pi || angle <= -pi) {
        // Division and truncation are exact operations: no libm fmod.
        real turns = static_cast<real>(static_cast<long long>(angle / two_pi));
        angle -= turns * two_pi;
        if (angle > pi) angle -= two_pi;
        if (angle <= -pi) angle += two_pi;
    }
    return angle;
}

}  // namespace arena::world
