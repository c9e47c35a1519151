#pragma once
// The world's random numbers: splitmix64 with an exact integer→float conversion, so every
// standard library and compiler draws the same sequence (std:: distributions differ between
// implementations; see DETERMINISM.md rule 4).
#include <cstdint>

#include "server/world/types.hpp"

namespace arena::world {

class rng {
public:
    explicit rng(uint64_t seed) : state_(seed) {}

    uint64_t next_u64() {
        uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }

    // Uniform in [0, 1): the top 24 bits scaled by 2^-24, exact in float.
    real next_unit() { return static_cast<real>(next_u64() >> 40) * (1.0f / 16777216.0f); }

    // Uniform in [lo, hi).
    real uniform(real lo, real hi) { return lo + (hi - lo) * next_unit(); }

    uint64_t state() const { return state_; }

private:
    uint64_t state_;
};

}  // namespace arena::world
