#include "scenes.hpp"

#include <cmath>

namespace arena::protocol::delta::test {
namespace {

constexpr float pi_f = 3.14159265f;

float wrap_pi(float a) {
  while (a > pi_f) a -= 2 * pi_f;
  while (a <= -pi_f) a += 2 * pi_f;
  return a;
}

}  // namespace

std::vector<sim_body> make_bodies(rng& r, motion kind, std::uint32_t count, float size,
                                  std::uint32_t first_id) {
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

}  // namespace arena::protocol::delta::test
