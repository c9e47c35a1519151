#pragma once
// Internal to the codec (encode.cpp, decode.cpp): the constants of the layout and the
// prediction both ends must compute bit for bit. Integer arithmetic only.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "protocol/delta/codec.hpp"

namespace arena::protocol::delta::format {

// 4 bits at the start of every encoding. 2: velocities in 1/32 m/s (1 had 1/256 m/s).
inline constexpr std::uint64_t version = 2;
inline constexpr unsigned version_bits = 4;
inline constexpr unsigned checksum_bits = 32;

// Each integer is an Exp-Golomb code whose order k the encoder picks per class and per
// snapshot (the best for that snapshot's values) and writes in the header.
enum code_class : unsigned {
    gap,               // unchanged baseline bodies before the next touched one
    velocity,          // zigzag(v − baseline v), per axis
    angular_velocity,  // zigzag(ω − baseline ω)
    position,          // zigzag(x − predicted x), per axis
    angle,             // zigzag(angle − predicted angle), wrapped to int16
    id_gap,            // added body: id − previous added id − 1 (the first: id)
    owner,             // added body, or a baseline body whose owner changed
    full_position,     // added body: zigzag(x), zigzag(y)
    full_velocity,     // added body: zigzag(vx), zigzag(vy)
    full_angular_velocity,
    class_count
};

// Field mask of a touched baseline body, 4 bits; 0 escapes to "removed" or "owner changed".
inline constexpr unsigned mask_bits = 4;
inline constexpr unsigned mask_velocity = 1;
inline constexpr unsigned mask_angular_velocity = 2;
inline constexpr unsigned mask_position = 4;
inline constexpr unsigned mask_angle = 8;

// Longer gaps than this predict nothing (both ends agree): 68 s at 60 Hz, far beyond any
// baseline a server keeps, and small enough that every numerator below stays under 2^52.
inline constexpr std::uint32_t max_predicted_ticks = 4095;

// floor(a / b + 1/2) for b > 0 and |a| < 2^51: rounding to nearest, ties up. Computed in
// double because a 64-bit integer division costs 40-90 cycles and this runs 3 times per body
// per client per snapshot. Exact, not approximate: n and b are exact doubles, IEEE division
// is off by at most one ulp of the quotient (≤ |q|·2^-52, in any rounding mode), and a
// non-integer n/b is at least 1/b from an integer, which that error cannot reach while
// |n| < 2^52; so floor() of the computed quotient is floor(n / b) on every compiler.
[[nodiscard]] inline std::int64_t round_div(std::int64_t a, std::int64_t b) noexcept {
    const std::int64_t n = a + b / 2;
    return static_cast<std::int64_t>(std::floor(static_cast<double>(n) / static_cast<double>(b)));
}

// Semi-implicit Euler (x += v_new·dt) under a constant acceleration over k ticks moves a body
// by dt·(v0·(k−1) + vk·(k+1))/2, where v0 is the baseline's velocity and vk the current one,
// which the decoder reads before the position. Exact for drifting and steadily thrusting
// bodies; reduces to k·v0·dt when the velocity is unchanged. Returns twice the displacement
// in velocity units × ticks; the callers divide by 2·tick_rate.
[[nodiscard]] constexpr std::int64_t trapezoid(std::int64_t v0, std::int64_t vk, elapsed_time e) noexcept {
    const std::int64_t k = std::min(e.ticks, max_predicted_ticks);
    if (k == 0 || e.tick_rate == 0) return 0;
    return v0 * (k - 1) + vk * (k + 1);
}

// Position units (1/256 m) from velocity units (1/32 m/s): × 8, ÷ 2·rate. |twice| < 2^44
// (int32 velocities, k < 2^12), so the numerator stays under 2^47 < 2^51 (round_div's bound).
inline constexpr std::int64_t position_units_per_velocity_unit = 8;
static_assert(position_scale / velocity_scale == position_units_per_velocity_unit);
[[nodiscard]] inline std::int64_t predict_displacement(std::int64_t v0, std::int64_t vk, elapsed_time e) noexcept {
    const std::int64_t twice = trapezoid(v0, vk, e);
    return twice == 0 ? 0 : round_div(twice * position_units_per_velocity_unit, 2 * std::int64_t{e.tick_rate});
}

// Angle units (2π/65536 rad) from angular velocity units (1/256 rad/s): × 256/(2π), as the
// fixed-point constant round(256/(2π) · 2^16) (|twice| < 2^29, so the product is < 2^51).
inline constexpr std::int64_t omega_to_angle_q16 = 2670177;
[[nodiscard]] inline std::int64_t predict_rotation(std::int64_t w0, std::int64_t wk, elapsed_time e) noexcept {
    const std::int64_t twice = trapezoid(w0, wk, e);
    return twice == 0 ? 0 : round_div(twice * omega_to_angle_q16, 2 * std::int64_t{e.tick_rate} << 16);
}

// Angles live on the circle: sums wrap modulo 65536 (C++20 defines the conversion).
[[nodiscard]] constexpr std::int16_t wrap_angle(std::int64_t a) noexcept {
    return static_cast<std::int16_t>(static_cast<std::uint16_t>(a & 0xffff));
}

}  // namespace arena::protocol::delta::format
