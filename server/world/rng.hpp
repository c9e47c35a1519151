#pragma once
// The world's random numbers: splitmix64 (splitmix64.hpp) with an exact integer→float
// conversion, so every standard library and compiler draws the same sequence (std::
// distributions differ between implementations; see docs/DETERMINISM.md).
#include <cstdint>

#include "server/world/splitmix64.hpp"
#include "server/world/types.hpp"

namespace arena::world {

class rng {
public:
    explicit rng(uint64_t seed) : gen_(seed) {}

    uint64_t next_u64() { return gen_.next(); }

    // Uniform in [0, 1): the top 24 bits scaled by 2^-24, exact in float.
    real next_unit() { return static_cast<real>(next_u64() >> 40) * (1.0f / 16777216.0f); }

    // Uniform in [lo, hi).
    real uniform(real lo, real hi) { return lo + (hi - lo) * next_unit(); }

    uint64_t state() const { return gen_.state(); }

private:
    splitmix64 gen_;
};

}  // namespace arena::world
