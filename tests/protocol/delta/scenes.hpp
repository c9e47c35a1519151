#pragma once
// Bodies for the delta tests: an integer PRNG, float bodies simulated like the world's
// semi-implicit Euler (drifting rocks, thrusting and turning ships, bodies at rest), and
// their quantised views. Test data only: libm's sin/cos are fine here.
#include <cstdint>
#include <vector>

#include "protocol/delta/quantize.hpp"
#include "server/world/splitmix64.hpp"

namespace arena::protocol::delta::test {

// The code base's splitmix64, with the conversions these tests draw.
class rng {
public:
    explicit rng(std::uint64_t seed) : s_(seed) {}
    std::uint64_t next() noexcept { return s_.next(); }
    double uniform() noexcept { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
    double uniform(double lo, double hi) noexcept { return lo + (hi - lo) * uniform(); }
    std::uint64_t below(std::uint64_t n) noexcept { return next() % n; }  // bias irrelevant here
    bool chance(double p) noexcept { return uniform() < p; }

private:
    world::splitmix64 s_;
};

enum class motion { rest, drift, player };

struct sim_body {
    std::uint32_t id = 0;
    std::uint32_t owner = 0;
    motion kind = motion::drift;
    float x = 0, y = 0, vx = 0, vy = 0, angle = 0, w = 0;
    float thrust = 0, turn = 0;  // players only, re-chosen every half second
};

// A square world of the given size (m) with `count` bodies of one kind, ids 1..count.
std::vector<sim_body> make_bodies(rng& r, motion kind, std::uint32_t count, float size, std::uint32_t first_id = 1);

// One world tick of dt seconds for every body (asteroids preset's ship: 10 kg, 200 N of
// thrust, 60 N·m of torque, drag ACd 0.5, angular damping 2/s; rocks keep v and ω).
void step(std::vector<sim_body>& bodies, rng& r, float dt);

// The quantised view, sorted by id (bodies are kept in id order).
std::vector<quantized_body> quantize_view(const std::vector<sim_body>& bodies);

// Integer views for the codec's property tests: a random body (mostly game-like values,
// sometimes the type's limits), and one snapshot interval of `ticks` ticks at `rate` over a
// view: most bodies move as predicted (up to rounding), some accelerate, jump, spin up or
// change owner; some leave, some join (fresh ids, some at the top of the range).
quantized_body random_body(rng& r, std::uint32_t id);
void evolve(std::vector<quantized_body>& view, rng& r, std::uint32_t ticks, std::uint32_t rate);

}  // namespace arena::protocol::delta::test
