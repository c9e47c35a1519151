#include "protocol/delta/quantize.hpp"

#include <cmath>
#include <limits>

namespace arena::protocol::delta {
namespace {

// Round to nearest, ties towards +∞, clamped to [lo, hi]; NaN → 0. v is a float times a
// power of two (or the angle's constant), so v + 0.5 is exact in double for every input
// that can round either way: floor() then gives the true nearest integer whatever the FPU's
// rounding mode.
std::int64_t round_clamped(double v, std::int64_t lo, std::int64_t hi) noexcept {
    if (v != v) return 0;  // NaN: a defined answer; NaN must never enter the world anyway
    const double r = std::floor(v + 0.5);
    if (r <= static_cast<double>(lo)) return lo;
    if (r >= static_cast<double>(hi)) return hi;
    return static_cast<std::int64_t>(r);
}

constexpr std::int64_t i32_min = std::numeric_limits<std::int32_t>::min();
constexpr std::int64_t i32_max = std::numeric_limits<std::int32_t>::max();
constexpr std::int64_t i16_min = std::numeric_limits<std::int16_t>::min();
constexpr std::int64_t i16_max = std::numeric_limits<std::int16_t>::max();

}  // namespace

std::int32_t quantize_position(float metres) noexcept {
    return static_cast<std::int32_t>(round_clamped(double{metres} * position_scale, i32_min, i32_max));
}

std::int32_t quantize_velocity(float metres_per_second) noexcept {
    return static_cast<std::int32_t>(round_clamped(double{metres_per_second} * velocity_scale, i32_min, i32_max));
}

std::int16_t quantize_angle(float radians) noexcept {
    // Clamp far outside any real angle (2^40 units ≈ 1.1e8 rad) so the int64 conversion is
    // defined; then wrap modulo 65536, which C++20 defines for the unsigned→signed cast.
    constexpr std::int64_t far = std::int64_t{1} << 40;
    const std::int64_t r = round_clamped(double{radians} * angle_scale, -far, far);
    return static_cast<std::int16_t>(static_cast<std::uint16_t>(r & 0xffff));
}

std::int16_t quantize_angular_velocity(float radians_per_second) noexcept {
    return static_cast<std::int16_t>(
        round_clamped(double{radians_per_second} * angular_velocity_scale, i16_min, i16_max));
}

// Integers divided by powers of two: exact in double, one rounding to float.
float dequantize_position(std::int32_t q) noexcept {
    return static_cast<float>(q / position_scale);
}

float dequantize_velocity(std::int32_t q) noexcept {
    return static_cast<float>(q / velocity_scale);
}

float dequantize_angle(std::int16_t q) noexcept {
    // −32768 and +32768 are the same direction; BodyState's range is (−π, π], so return +π.
    const std::int32_t unit = q == std::numeric_limits<std::int16_t>::min() ? 32768 : q;
    return static_cast<float>(unit * angle_unit);
}

float dequantize_angular_velocity(std::int16_t q) noexcept {
    return static_cast<float>(q / angular_velocity_scale);
}

quantized_body quantize(const BodyState& b) noexcept {
    return quantized_body{b.id(),
                          b.owner(),
                          quantize_position(b.x()),
                          quantize_position(b.y()),
                          quantize_velocity(b.vx()),
                          quantize_velocity(b.vy()),
                          quantize_angle(b.angle()),
                          quantize_angular_velocity(b.angular_velocity())};
}

BodyState dequantize(const quantized_body& q) noexcept {
    return BodyState(q.id, q.owner, dequantize_position(q.x), dequantize_position(q.y), dequantize_velocity(q.vx),
                     dequantize_velocity(q.vy), dequantize_angle(q.angle),
                     dequantize_angular_velocity(q.angular_velocity));
}

}  // namespace arena::protocol::delta
