#include "scenes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace arena::protocol::delta::test {
namespace {

constexpr float pi_f = 3.14159265f;

float wrap_pi(float a) {
    while (a > pi_f) a -= 2 * pi_f;
    while (a <= -pi_f) a += 2 * pi_f;
    return a;
}

}  // namespace

std::vector<sim_body> make_bodies(rng& r, motion kind, std::uint32_t count, float size, std::uint32_t first_id) {
    std::vector<sim_body> out;
    out.reserve(count);
    for (std::uint32_t i = 0; i < count; ++i) {
        sim_body b;
        b.id = first_id + i;
        b.kind = kind;
        b.x = static_cast<float>(r.uniform(0, size));
        b.y = static_cast<float>(r.uniform(0, size));
        b.angle = static_cast<float>(r.uniform(-pi_f, pi_f));
        if (kind == motion::drift) {
            b.vx = static_cast<float>(r.uniform(-6, 6));  // asteroids preset: rocks up to 6 m/s
            b.vy = static_cast<float>(r.uniform(-6, 6));
            b.w = static_cast<float>(r.uniform(-1, 1));
        } else if (kind == motion::player) {
            b.owner = 1000 + i;
            b.vx = static_cast<float>(r.uniform(-20, 20));
            b.vy = static_cast<float>(r.uniform(-20, 20));
        }
        out.push_back(b);
    }
    return out;
}

void step(std::vector<sim_body>& bodies, rng& r, float dt) {
    for (sim_body& b : bodies) {
        if (b.kind == motion::rest) continue;
        if (b.kind == motion::player) {
            if (r.chance(dt * 2)) {  // a new control about twice a second
                b.thrust = r.chance(0.7) ? 1.0f : 0.0f;
                b.turn = static_cast<float>(static_cast<int>(r.below(3)) - 1);
            }
            const float inertia = 0.5f * 10 * 1.5f * 1.5f;
            b.w += (b.turn * 60 / inertia - 2 * b.w) * dt;
            const float speed = std::sqrt(b.vx * b.vx + b.vy * b.vy);
            const float drag = 0.5f * 1.2f * 0.5f * speed / 10;
            b.vx += (b.thrust * 20 * std::cos(b.angle) - drag * b.vx) * dt;
            b.vy += (b.thrust * 20 * std::sin(b.angle) - drag * b.vy) * dt;
        }
        b.x += b.vx * dt;
        b.y += b.vy * dt;
        b.angle = wrap_pi(b.angle + b.w * dt);
    }
}

std::vector<quantized_body> quantize_view(const std::vector<sim_body>& bodies) {
    std::vector<quantized_body> out;
    out.reserve(bodies.size());
    for (const sim_body& b : bodies) {
        out.push_back(quantize(BodyState(b.id, b.owner, b.x, b.y, b.vx, b.vy, b.angle, b.w)));
    }
    return out;
}

namespace {

constexpr std::int32_t i32min = std::numeric_limits<std::int32_t>::min();
constexpr std::int32_t i32max = std::numeric_limits<std::int32_t>::max();

std::int32_t clamp32(std::int64_t v) {
    return static_cast<std::int32_t>(std::clamp<std::int64_t>(v, i32min, i32max));
}

// A value of any magnitude: mostly game-like, sometimes at or near the type's limits.
std::int32_t wild32(rng& r) {
    switch (r.below(6)) {
        case 0:
            return i32min;
        case 1:
            return i32max;
        case 2:
            return static_cast<std::int32_t>(r.next());
        default:
            return static_cast<std::int32_t>(r.below(200000)) - 100000;
    }
}

}  // namespace

quantized_body random_body(rng& r, std::uint32_t id) {
    quantized_body b;
    b.id = id;
    b.owner = r.chance(0.3) ? static_cast<std::uint32_t>(r.below(2000)) : 0;
    if (r.chance(0.05)) b.owner = std::numeric_limits<std::uint32_t>::max();
    const bool wild = r.chance(0.05);
    b.x = wild ? wild32(r) : static_cast<std::int32_t>(r.below(400 * 256));
    b.y = wild ? wild32(r) : static_cast<std::int32_t>(r.below(400 * 256));
    b.vx = wild ? wild32(r) : static_cast<std::int32_t>(r.below(12 * 256)) - 6 * 256;
    b.vy = wild ? wild32(r) : static_cast<std::int32_t>(r.below(12 * 256)) - 6 * 256;
    b.angle = static_cast<std::int16_t>(r.next());
    b.angular_velocity =
        wild ? static_cast<std::int16_t>(r.next()) : static_cast<std::int16_t>(static_cast<int>(r.below(512)) - 256);
    return b;
}

// One snapshot interval of `ticks` ticks at `rate`: most bodies move as predicted (up to
// rounding), some accelerate, jump, spin up, change owner; some leave, some join.
void evolve(std::vector<quantized_body>& view, rng& r, std::uint32_t ticks, std::uint32_t rate) {
    std::vector<quantized_body> next;
    next.reserve(view.size() + 64);
    for (quantized_body b : view) {
        if (r.chance(0.01)) continue;  // leaves
        const double roll = r.uniform();
        if (roll < 0.15) {  // unchanged: at rest
            b.vx = b.vy = 0;
            b.angular_velocity = 0;
        } else if (roll < 0.6) {  // drifting
            b.x = clamp32(b.x + std::int64_t{b.vx} * ticks / rate);
            b.y = clamp32(b.y + std::int64_t{b.vy} * ticks / rate);
        } else if (roll < 0.9) {  // thrusting and turning
            b.vx = clamp32(b.vx + static_cast<std::int64_t>(r.below(513)) - 256);
            b.vy = clamp32(b.vy + static_cast<std::int64_t>(r.below(513)) - 256);
            b.x = clamp32(b.x + std::int64_t{b.vx} * ticks / rate + static_cast<std::int64_t>(r.below(5)) - 2);
            b.y = clamp32(b.y + std::int64_t{b.vy} * ticks / rate);
            b.angular_velocity = static_cast<std::int16_t>(
                std::clamp<int>(b.angular_velocity + static_cast<int>(r.below(101)) - 50, -32768, 32767));
            b.angle = static_cast<std::int16_t>(b.angle + b.angular_velocity / 8);
        } else {  // anything: teleport, wild values, owner change
            const quantized_body w = random_body(r, b.id);
            b = r.chance(0.5) ? w : quantized_body{b.id, w.owner, b.x, w.y, b.vx, w.vy, w.angle, b.angular_velocity};
        }
        next.push_back(b);
    }
    // Joins: fresh ids (some far above, some reusing the gaps of bodies that left).
    const std::uint64_t joins = r.below(40);
    for (std::uint64_t k = 0; k < joins; ++k) {
        const std::uint32_t id =
            r.chance(0.1) ? std::numeric_limits<std::uint32_t>::max() - static_cast<std::uint32_t>(r.below(4))
                          : static_cast<std::uint32_t>(r.below(20000));
        const auto at = std::lower_bound(next.begin(), next.end(), id,
                                         [](const quantized_body& b, std::uint32_t v) { return b.id < v; });
        if (at != next.end() && at->id == id) continue;
        next.insert(at, random_body(r, id));
    }
    view = std::move(next);
}

}  // namespace arena::protocol::delta::test
