#pragma once
// splitmix64 (Steele, Lea and Flood), the one integer PRNG of the code base: the world's rng
// (rng.hpp), the bots' behaviours and the tests' scenes draw from it. Integer-only, so every
// compiler, standard library and architecture gives the same sequence (std:: engines and
// distributions differ between implementations; docs/DETERMINISM.md). Header-only and
// standard library only.
#include <cstdint>

namespace arena::world {

class splitmix64 {
public:
    // The increment: 2^64 / φ, odd. Also a good constant to spread seeds apart.
    static constexpr std::uint64_t gamma = 0x9e3779b97f4a7c15ULL;

    constexpr explicit splitmix64(std::uint64_t seed) noexcept : state_(seed) {}

    constexpr std::uint64_t next() noexcept {
        std::uint64_t z = (state_ += gamma);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }

    [[nodiscard]] constexpr std::uint64_t state() const noexcept { return state_; }

private:
    std::uint64_t state_;
};

}  // namespace arena::world
