#include "client_sim/behavior.hpp"

#include <algorithm>
#include <cmath>

#include "protocol/decode.hpp"
#include "server/world/broadphase.hpp"
#include "server/world/splitmix64.hpp"
#include "server/world/trig.hpp"

namespace arena::bots {

namespace {

using world::player_input;
using world::vec2;

// One stream per (seed, index): splitmix64 of the seed, offset by the index times the golden
// ratio constant, so that neighbouring bots and neighbouring seeds draw unrelated numbers.
std::uint64_t stream_seed(std::uint64_t seed, std::uint32_t index) {
    world::splitmix64 mix(seed);
    return mix.next() ^ (world::splitmix64::gamma * (std::uint64_t{index} + 1));
}

float clamp_unit(float v) {
    return std::clamp(v, -1.0f, 1.0f);
}

// A seek waypoint counts as reached within this distance, m.
constexpr float waypoint_reached = 5.0f;

// The Asteroids rules' fire button (games/asteroids/asteroids_rules.hpp; bit 0 is the boost).
constexpr std::uint8_t button_fire = 1u << 1;
// Their bullets' speed from rest, m/s (J / m_bullet): how far ahead of its prey a hunter aims.
constexpr float bullet_speed = 40.0f;
// A hunter ignores bodies this much faster than itself (bullets, its own included), m/s.
constexpr float bullet_like_speed = 25.0f;
// Closer than this to the edge-less centre of its prey, a hunter steers away (a rock would kill it), m.
constexpr float danger_distance = 12.0f;
// It fires when its facing is within acos(0.98) ≈ 11° of the aim and the prey this near, m.
constexpr float fire_range = 80.0f;

}  // namespace

std::optional<behavior_choice> parse_behavior(std::string_view name) {
    if (name == "random") return behavior_choice::random;
    if (name == "seek") return behavior_choice::seek;
    if (name == "orbit") return behavior_choice::orbit;
    if (name == "idle") return behavior_choice::idle;
    if (name == "mixed") return behavior_choice::mixed;
    if (name == "hunter") return behavior_choice::hunter;
    if (name == "game") return behavior_choice::game;
    return std::nullopt;
}

std::string_view to_string(behavior_kind kind) {
    switch (kind) {
        case behavior_kind::random:
            return "random";
        case behavior_kind::seek:
            return "seek";
        case behavior_kind::orbit:
            return "orbit";
        case behavior_kind::idle:
            return "idle";
        case behavior_kind::hunter:
            return "hunter";
        case behavior_kind::game:
            return "game";
    }
    return "unknown";
}

behavior_kind resolve_behavior(behavior_choice choice, std::uint32_t index) {
    switch (choice) {
        case behavior_choice::random:
            return behavior_kind::random;
        case behavior_choice::seek:
            return behavior_kind::seek;
        case behavior_choice::orbit:
            return behavior_kind::orbit;
        case behavior_choice::idle:
            return behavior_kind::idle;
        case behavior_choice::hunter:
            return behavior_kind::hunter;
        case behavior_choice::game:
            return behavior_kind::game;
        case behavior_choice::mixed:
            break;
    }
    static constexpr behavior_kind cycle[] = {behavior_kind::random, behavior_kind::seek, behavior_kind::orbit,
                                              behavior_kind::idle, behavior_kind::hunter};
    return cycle[index % 5];
}

behavior::behavior(behavior_kind kind, std::uint64_t seed, std::uint32_t index, const world::world_config& config)
    : kind_(kind), config_(config), rng_(stream_seed(seed, index)) {
    // Every kind draws its parameters here, in the same order, so that a bot's stream does
    // not depend on which kind it was given.
    const vec2 centre = random_point();
    centre_ = centre;
    radius_ = rng_.uniform(0.05f, 0.2f) * std::min(config_.size.x(), config_.size.y());
    target_ = random_point();
}

vec2 behavior::random_point() {
    // One draw per statement: argument evaluation order differs between compilers.
    const float x = rng_.uniform(0.1f, 0.9f) * config_.size.x();
    const float y = rng_.uniform(0.1f, 0.9f) * config_.size.y();
    return {x, y};
}

player_input behavior::next(const observation& seen) {
    switch (kind_) {
        case behavior_kind::idle:
            return {};
        case behavior_kind::random:
            return random_walk();
        case behavior_kind::seek:
        case behavior_kind::game:  // a game without a bot of its own (client_core plays the one it has)
            return seen.own ? seek(*seen.own) : player_input{};
        case behavior_kind::orbit:
            return seen.own ? orbit(*seen.own) : player_input{};
        case behavior_kind::hunter:
            return seen.own ? hunt(*seen.own) : player_input{};
    }
    return {};
}

player_input behavior::random_walk() {
    return wander_.next(rng_);
}

void behavior::observe(std::span<const protocol::BodyState> bodies, std::uint32_t own_id) {
    if (kind_ == behavior_kind::hunter) observe_prey(bodies, own_id);
    if (kind_ != behavior_kind::seek && kind_ != behavior_kind::game) return;
    if (target_id_ != 0) {
        if (const protocol::BodyState* at = protocol::find_body(bodies, target_id_)) {
            target_ = vec2{at->x(), at->y()};
            return;
        }
        target_id_ = 0;  // it left: pick another below, or head for the last place it was seen
        target_is_waypoint_ = true;
    }
    if (bodies.size() < 2) return;
    std::size_t pick = static_cast<std::size_t>(rng_.next_u64() % bodies.size());
    if (bodies[pick].id() == own_id) pick = (pick + 1) % bodies.size();
    target_id_ = bodies[pick].id();
    target_ = vec2{bodies[pick].x(), bodies[pick].y()};
    target_is_waypoint_ = false;
}

player_input behavior::seek(const world::body& own) {
    vec2 to = world::displacement(own.position, *target_, config_);
    if (target_is_waypoint_ && to.squaredNorm() < waypoint_reached * waypoint_reached) {
        target_ = random_point();
        to = world::displacement(own.position, *target_, config_);
    }
    if (to.squaredNorm() < 1e-6f) return {};
    return steer(own, to);
}

void behavior::observe_prey(std::span<const protocol::BodyState> bodies, std::uint32_t own_id) {
    const protocol::BodyState* own = protocol::find_body(bodies, own_id);
    prey_.reset();
    if (own == nullptr) return;
    const vec2 at{own->x(), own->y()};
    const vec2 moving{own->vx(), own->vy()};
    float nearest = 0;
    for (const protocol::BodyState& b : bodies) {
        if (b.id() == own_id) continue;
        const vec2 v{b.vx(), b.vy()};
        if ((v - moving).squaredNorm() > bullet_like_speed * bullet_like_speed) continue;
        const float d = world::displacement(at, vec2{b.x(), b.y()}, config_).squaredNorm();
        if (prey_ && d >= nearest) continue;
        nearest = d;
        prey_ = vec2{b.x(), b.y()};
        prey_velocity_ = v;
    }
}

player_input behavior::hunt(const world::body& own) {
    if (!prey_) return orbit(own);  // nothing in view: patrol
    const vec2 to = world::displacement(own.position, *prey_, config_);
    const float distance = std::sqrt(to.squaredNorm());
    if (distance < 1e-3f) return {};
    if (distance < danger_distance) return steer(own, -to);
    // Lead the prey by its velocity relative to ours over the bullet's flight time.
    const float flight = distance / bullet_speed;
    const vec2 aim = to + (prey_velocity_ - own.velocity) * flight;
    if (aim.squaredNorm() < 1e-6f) return {};
    player_input in = steer(own, aim);
    const world::cos_sin facing = world::compute_cos_sin(own.angle);
    const float aligned = (facing.c * aim.x() + facing.s * aim.y()) / std::sqrt(aim.squaredNorm());
    if (aligned > 0.98f && distance < fire_range) in.buttons = static_cast<std::uint8_t>(in.buttons | button_fire);
    return in;
}

player_input behavior::orbit(const world::body& own) {
    const vec2 out = world::displacement(centre_, own.position, config_);
    const float distance = std::sqrt(out.squaredNorm());
    if (distance < 1e-3f) return steer(own, vec2{1, 0});  // at the centre: leave it in any direction
    const vec2 radial = out / distance;
    const vec2 tangent{-radial.y(), radial.x()};  // counter-clockwise
    // Head along the circle, leaning inwards when outside it and outwards when inside.
    const float drift = std::clamp((distance - radius_) / radius_, -1.0f, 1.0f);
    return steer(own, tangent - drift * radial);
}

player_input behavior::steer(const world::body& own, const vec2& direction) {
    const float length = std::sqrt(direction.squaredNorm());
    const vec2 d = direction / length;
    if (!config_.control.thrust_along_facing) {
        // Runner (platformer): thrust pushes along +x; jump when the goal is above.
        const float thrust = clamp_unit(2.0f * d.x());
        const bool jump = d.y() > 0.5f && rng_.next_u64() % 30 == 0;
        return {thrust, 0.0f, jump ? world::button_impulse : std::uint8_t{0}};
    }
    // Ship: turn by the sine of the heading error (cross product), damped by the spin so it
    // does not oscillate; thrust when roughly facing the goal.
    const world::cos_sin facing = world::compute_cos_sin(own.angle);
    const float cross = facing.c * d.y() - facing.s * d.x();
    const float dot = facing.c * d.x() + facing.s * d.y();
    const float turn = clamp_unit(3.0f * (dot < 0 ? (cross < 0 ? -1.0f : 1.0f) : cross) - 0.5f * own.angular_velocity);
    // Slow down near the top speed so that the bot can still turn into the goal.
    const float speed = std::sqrt(own.velocity.squaredNorm());
    const float thrust = dot > 0.7f ? (speed < 15.0f ? 1.0f : 0.3f) : 0.0f;
    return {thrust, turn, 0};
}

}  // namespace arena::bots
