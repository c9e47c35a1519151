// Quantisation: each field's error stays within its documented bound, rounding follows the
// written rule, out-of-range and non-finite input clamps, and dequantisation is always finite.
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "protocol/delta/quantize.hpp"
#include "scenes.hpp"

namespace ad = arena::protocol::delta;

namespace {

constexpr float inf = std::numeric_limits<float>::infinity();
constexpr float qnan = std::numeric_limits<float>::quiet_NaN();

// Half a float ulp at v: what converting an exact result back to float may add.
double half_ulp(double v) {
    const float f = static_cast<float>(std::fabs(v));
    return (std::nextafter(f, inf) - f) * 0.5;
}

// Distance on the circle, in (−π, π].
double angle_distance(double a, double b) {
    double d = std::fmod(a - b, 2 * ad::pi);
    if (d > ad::pi) d -= 2 * ad::pi;
    if (d <= -ad::pi) d += 2 * ad::pi;
    return std::fabs(d);
}

}  // namespace

TEST_CASE("Position errors stay within 1/512 m and velocity errors within 1/64 m/s across a 10 km world",
          "[protocol][delta]") {
    ad::test::rng r(1);
    double worst_p = 0, worst_v = 0;
    for (int i = 0; i < 200000; ++i) {
        const auto x = static_cast<float>(r.uniform(-10000, 10000));
        const auto v = static_cast<float>(r.uniform(-500, 500));
        worst_p = std::max(worst_p, std::fabs(ad::dequantize_position(ad::quantize_position(x)) - double{x}));
        worst_v = std::max(worst_v, std::fabs(ad::dequantize_velocity(ad::quantize_velocity(v)) - double{v}));
    }
    INFO("worst position error " << worst_p << " m, velocity " << worst_v << " m/s");
    CHECK(worst_p <= ad::max_position_error);
    CHECK(worst_v <= ad::max_velocity_error);
    CHECK(worst_p > 0.9 * ad::max_position_error);  // the bound is tight, not loose
    CHECK(worst_v > 0.9 * ad::max_velocity_error);
}

TEST_CASE("Far positions keep the bound plus the float's own half ulp", "[protocol][delta]") {
    for (float x : {65536.0f, 1.0e5f, -3.3e6f, 8.0e6f, -8.3e6f}) {
        const double back = ad::dequantize_position(ad::quantize_position(x));
        CHECK(std::fabs(back - x) <= ad::max_position_error + half_ulp(x));
    }
}

TEST_CASE("Angle error stays within π/65536 rad, across the ±π seam too", "[protocol][delta]") {
    ad::test::rng r(2);
    double worst = 0;
    for (int i = 0; i < 200000; ++i) {
        const auto a = static_cast<float>(r.uniform(-ad::pi, ad::pi));
        worst = std::max(worst, angle_distance(ad::dequantize_angle(ad::quantize_angle(a)), a));
    }
    for (float a : {3.14159265f, -3.14159265f, 3.1415f, -3.1415f, 0.0f, -0.0f, 1e-30f}) {
        worst = std::max(worst, angle_distance(ad::dequantize_angle(ad::quantize_angle(a)), a));
    }
    INFO("worst angle error " << worst << " rad");
    // The product by 32768/π rounds once in double, and the result once to float (≤ 1.2e-7).
    CHECK(worst <= ad::max_angle_error + 2.5e-7);
}

TEST_CASE("Angles outside −π < a ≤ π wrap onto the circle", "[protocol][delta]") {
    CHECK(ad::quantize_angle(static_cast<float>(3 * ad::pi)) == ad::quantize_angle(static_cast<float>(ad::pi)));
    CHECK(ad::quantize_angle(7.0f) == ad::quantize_angle(static_cast<float>(7.0 - 2 * ad::pi)));
    CHECK(ad::quantize_angle(-100.0f) == ad::quantize_angle(static_cast<float>(-100.0 + 32 * ad::pi)));
}

TEST_CASE("The half-turn −32768 dequantises to +π, keeping BodyState's −π < a ≤ π", "[protocol][delta]") {
    CHECK(ad::dequantize_angle(std::numeric_limits<std::int16_t>::min()) == static_cast<float>(ad::pi));
    CHECK(ad::dequantize_angle(32767) < static_cast<float>(ad::pi));
    CHECK(ad::dequantize_angle(-32767) > static_cast<float>(-ad::pi));
}

TEST_CASE("Angular velocity error stays within 1/512 rad/s and clamps at ±128 rad/s", "[protocol][delta]") {
    ad::test::rng r(3);
    double worst = 0;
    for (int i = 0; i < 200000; ++i) {
        const auto w = static_cast<float>(r.uniform(-127.9, 127.9));
        worst =
            std::max(worst, std::fabs(ad::dequantize_angular_velocity(ad::quantize_angular_velocity(w)) - double{w}));
    }
    CHECK(worst <= ad::max_angular_velocity_error);
    CHECK(ad::quantize_angular_velocity(1000.0f) == 32767);
    CHECK(ad::quantize_angular_velocity(-1000.0f) == -32768);
}

TEST_CASE("Rounding is to nearest with ties towards +infinity", "[protocol][delta]") {
    CHECK(ad::quantize_position(0.5f / 256) == 1);
    CHECK(ad::quantize_position(-0.5f / 256) == 0);
    CHECK(ad::quantize_position(1.5f / 256) == 2);
    CHECK(ad::quantize_position(-1.5f / 256) == -1);
    CHECK(ad::quantize_position(std::nextafter(0.5f / 256, 0.0f)) == 0);
    CHECK(ad::quantize_position(-0.0f) == 0);
    CHECK(ad::quantize_velocity(2.25f) == 72);  // 1/32 m/s
    CHECK(ad::quantize_velocity(0.5f / 32) == 1);
    CHECK(ad::quantize_velocity(-0.5f / 32) == 0);
    CHECK(ad::quantize_angular_velocity(-0.5f / 256) == 0);
}

TEST_CASE("Huge and non-finite input clamps (NaN to 0), never undefined", "[protocol][delta]") {
    constexpr auto i32max = std::numeric_limits<std::int32_t>::max();
    constexpr auto i32min = std::numeric_limits<std::int32_t>::min();
    CHECK(ad::quantize_position(inf) == i32max);
    CHECK(ad::quantize_position(-inf) == i32min);
    CHECK(ad::quantize_position(1e30f) == i32max);
    CHECK(ad::quantize_position(-1e30f) == i32min);
    CHECK(ad::quantize_position(qnan) == 0);
    CHECK(ad::quantize_velocity(std::numeric_limits<float>::max()) == i32max);
    CHECK(ad::quantize_velocity(qnan) == 0);
    CHECK(ad::quantize_angle(qnan) == 0);
    CHECK(ad::quantize_angular_velocity(qnan) == 0);
    CHECK(ad::quantize_angular_velocity(-inf) == -32768);
    // Defined, whatever the value: the angle of an infinite or huge input.
    (void)ad::quantize_angle(inf);
    (void)ad::quantize_angle(-1e38f);
}

TEST_CASE("Dequantisation is finite for every int16 and the int32 extremes", "[protocol][delta]") {
    for (std::int32_t q = -32768; q <= 32767; ++q) {
        REQUIRE(std::isfinite(ad::dequantize_angle(static_cast<std::int16_t>(q))));
        REQUIRE(std::isfinite(ad::dequantize_angular_velocity(static_cast<std::int16_t>(q))));
    }
    for (std::int32_t q :
         {std::numeric_limits<std::int32_t>::min(), -1, 0, 1, std::numeric_limits<std::int32_t>::max()}) {
        CHECK(std::isfinite(ad::dequantize_position(q)));
        CHECK(std::isfinite(ad::dequantize_velocity(q)));
    }
}

TEST_CASE("quantize(dequantize(q)) == q: the quantised view is a fixed point", "[protocol][delta]") {
    ad::test::rng r(4);
    for (int i = 0; i < 100000; ++i) {
        // Positions within ±65 536 m, where the float holds every 1/256 exactly.
        const ad::quantized_body q{static_cast<std::uint32_t>(r.next()),
                                   static_cast<std::uint32_t>(r.next()),
                                   static_cast<std::int32_t>(r.below(1u << 25)) - (1 << 24),
                                   static_cast<std::int32_t>(r.below(1u << 25)) - (1 << 24),
                                   static_cast<std::int32_t>(r.below(1u << 25)) - (1 << 24),
                                   static_cast<std::int32_t>(r.below(1u << 25)) - (1 << 24),
                                   static_cast<std::int16_t>(r.next()),
                                   static_cast<std::int16_t>(r.next())};
        REQUIRE(ad::quantize(ad::dequantize(q)) == q);
    }
}
