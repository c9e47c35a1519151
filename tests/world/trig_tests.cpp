#include <catch2/catch.hpp>
#include <cmath>

#include "server/world/trig.hpp"

using namespace arena::world;

TEST_CASE("compute_cos_sin agrees with libm to float precision", "[world][trig]") {
    // Over (−π, π], the range the world keeps angles in.
    for (int k = -314; k <= 314; ++k) {
        const real a = static_cast<real>(k) * 0.01f;
        const cos_sin cs = compute_cos_sin(a);
        INFO("angle " << a);
        CHECK(cs.c == Approx(std::cos(static_cast<double>(a))).margin(2e-7));
        CHECK(cs.s == Approx(std::sin(static_cast<double>(a))).margin(2e-7));
    }
}

TEST_CASE("wrap_angle keeps angles in -pi < a <= pi", "[world][trig]") {
    for (real a : {0.0f, 3.2f, -3.2f, 100.0f, -100.0f, 7.0f, pi, -pi}) {
        const real w = wrap_angle(a);
        CHECK(w > -pi);
        CHECK(w <= pi);
        CHECK(std::cos(static_cast<double>(w)) == Approx(std::cos(static_cast<double>(a))).margin(1e-4));
    }
}

TEST_CASE("compute_cos_sin of angles outside -pi < a <= pi loses only the float wrap's rounding", "[world][trig]") {
    for (int k = -2000; k <= 2000; k += 7) {
        const real a = static_cast<real>(k) * 0.01f;
        const cos_sin cs = compute_cos_sin(a);
        CHECK(cs.c == Approx(std::cos(static_cast<double>(a))).margin(1e-5));
        CHECK(cs.s == Approx(std::sin(static_cast<double>(a))).margin(1e-5));
    }
}
