#pragma once
// Quantisation: the integers the server sends instead of BodyState's floats. The server
// keeps this quantised view as the one truth it sends, so server and client agree on every
// bit a client can see, and the delta codec (codec.hpp) works on exact integers.
//
// Resolutions (README.md has the table) are chosen for worlds up to a few km:
//   position          1/256 m      int32  range ±8 388 km   max error 1/512 m  (≈ 2 mm)
//   velocity          1/32 m/s     int32  range ±67 108 km/s max error 1/64 m/s (≈ 16 mm/s)
//   angle             2π/65536 rad int16  the whole circle  max error π/65536 rad (≈ 4.8e-5)
//   angular velocity  1/256 rad/s  int16  range ±128 rad/s  max error 1/512 rad/s
// Rounding is to nearest, ties towards +∞, computed as floor(v + 0.5) on a double: exact and
// independent of the FPU rounding mode (std::nearbyint/lrint are not). Out-of-range values
// clamp; NaN quantises to 0. Dequantisation never produces NaN or infinity.
#include <cstdint>

#include "protocol/arena_generated.h"

namespace arena::protocol::delta {

// 28 bytes (BodyState: 32). Field order follows BodyState.
struct quantized_body {
    std::uint32_t id = 0;
    std::uint32_t owner = 0;
    std::int32_t x = 0;                 // 1/256 m
    std::int32_t y = 0;                 // 1/256 m
    std::int32_t vx = 0;                // 1/32 m/s
    std::int32_t vy = 0;                // 1/32 m/s
    std::int16_t angle = 0;             // 2π/65536 rad; −32768 is +π (BodyState's range is (−π, π])
    std::int16_t angular_velocity = 0;  // 1/256 rad/s

    friend bool operator==(const quantized_body&, const quantized_body&) = default;
};

// Units per SI unit.
inline constexpr double position_scale = 256.0;  // per m
// Velocities are coarser than positions: positions are sent with their own residual, so a
// velocity error only shifts a prediction by error × elapsed time (1/64 m/s × 0.15 s ≈ 2 mm,
// a position unit), while each finer bit would cost two bits per moving body per snapshot.
// 1/32 m/s instead of 1/256 saved 17 % of a thrusting player's bytes ("[size]" tests).
inline constexpr double velocity_scale = 32.0;           // per m/s
inline constexpr double angular_velocity_scale = 256.0;  // per rad/s
// 2π/65536 rad per unit; written out (not computed with libm) so every compiler agrees.
inline constexpr double pi = 3.14159265358979323846;
inline constexpr double angle_unit = pi / 32768.0;   // rad
inline constexpr double angle_scale = 32768.0 / pi;  // units per rad

// Worst-case error of quantize then dequantize, before the float conversion of the result
// (which is exact for |position| < 65 536 m and adds half a float ulp beyond).
inline constexpr double max_position_error = 0.5 / position_scale;                  // m
inline constexpr double max_velocity_error = 0.5 / velocity_scale;                  // m/s
inline constexpr double max_angle_error = 0.5 * angle_unit;                         // rad
inline constexpr double max_angular_velocity_error = 0.5 / angular_velocity_scale;  // rad/s

[[nodiscard]] std::int32_t quantize_position(float metres) noexcept;
[[nodiscard]] std::int32_t quantize_velocity(float metres_per_second) noexcept;
// Any finite angle; wraps to the circle (|angle| beyond ~1e8 rad clamps first, still defined).
[[nodiscard]] std::int16_t quantize_angle(float radians) noexcept;
// Clamps to ±128 rad/s: faster spins alias at any snapshot rate anyway (at 20 Hz a body
// turning more than π per snapshot, 63 rad/s, cannot be told from one turning backwards).
[[nodiscard]] std::int16_t quantize_angular_velocity(float radians_per_second) noexcept;

[[nodiscard]] float dequantize_position(std::int32_t q) noexcept;
[[nodiscard]] float dequantize_velocity(std::int32_t q) noexcept;
[[nodiscard]] float dequantize_angle(std::int16_t q) noexcept;  // in (−π, π] as floats go
[[nodiscard]] float dequantize_angular_velocity(std::int16_t q) noexcept;

[[nodiscard]] quantized_body quantize(const BodyState& body) noexcept;
[[nodiscard]] BodyState dequantize(const quantized_body& body) noexcept;

}  // namespace arena::protocol::delta
