// The solver's lanes (server/world/wide.hpp): each lane gives the bits the scalar expression
// gives, signed zeros and NaN included, so that the wide solve is the same on every target.
#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "server/world/wide.hpp"

using namespace arena::world;

namespace {

const std::vector<real> samples = {0.0f,
                                   -0.0f,
                                   1.0f,
                                   -1.0f,
                                   0.5f,
                                   -2.5f,
                                   1e-30f,
                                   -1e30f,
                                   std::numeric_limits<real>::infinity(),
                                   std::numeric_limits<real>::quiet_NaN()};

uint32_t bits(real x) {
    return std::bit_cast<uint32_t>(x);
}

}  // namespace

TEST_CASE("max, min and clamp lane by lane are std::max, std::min and std::clamp, to the bit", "[world][wide]") {
    for (const real a : samples) {
        for (const real b : samples) {
            const wide wa = splat(a), wb = splat(b);
            const wide mx = max(wa, wb), mn = min(wa, wb);
            for (size_t i = 0; i < wide_lanes; ++i) {
                INFO(a << ", " << b);
                CHECK(bits(mx[i]) == bits(std::max(a, b)));
                CHECK(bits(mn[i]) == bits(std::min(a, b)));
            }
            if (std::isnan(a) || std::isnan(b) || b < a) continue;
            for (const real v : samples) {
                const wide c = clamp(splat(v), wa, wb);
                INFO(v << " in [" << a << ", " << b << "]");
                CHECK(bits(c[0]) == bits(std::clamp(v, a, b)));
            }
        }
    }
}

TEST_CASE("select picks whole lanes by the mask, and wide_of and mask_of fill lane i from i", "[world][wide]") {
    const wide lanes = wide_of([](size_t i) { return static_cast<real>(i) + 0.25f; });
    const wide_mask odd = mask_of([](size_t i) { return i % 2 == 1; });
    const wide picked = select(odd, lanes, splat(-0.0f));
    for (size_t i = 0; i < wide_lanes; ++i) {
        CHECK(lanes[i] == static_cast<real>(i) + 0.25f);
        CHECK(odd[i] == (i % 2 == 1 ? -1 : 0));
        CHECK(bits(picked[i]) == (i % 2 == 1 ? bits(lanes[i]) : bits(-0.0f)));
    }
}

TEST_CASE("lane arithmetic is the scalar arithmetic of each lane", "[world][wide]") {
    const wide a = wide_of([](size_t i) { return 1.0f / (3.0f + static_cast<real>(i)); });
    const wide b = wide_of([](size_t i) { return 0.1f * static_cast<real>(i + 1); });
    const wide r = (a * b + a) / b - a;
    for (size_t i = 0; i < wide_lanes; ++i) {
        const real x = a[i], y = b[i];
        const real product = x * y;  // one rounding per operation, as the lanes do
        const real sum = product + x;
        CHECK(bits(r[i]) == bits(sum / y - x));
    }
}
