#pragma once
// What each bot does with its controls. A behaviour is a pure function of (kind, seed, bot
// index) and what it observes: the same observations give the same inputs on every machine,
// because its randomness is arena::world::rng (never a std:: distribution) and its steering
// uses only + − × ÷, sqrt and the world's own polynomial cos/sin.
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "protocol/arena_generated.h"
#include "scenes/sticks.hpp"
#include "server/world/body.hpp"
#include "server/world/config.hpp"
#include "server/world/input.hpp"
#include "server/world/rng.hpp"

namespace arena::bots {

enum class behavior_kind : std::uint8_t {
    random,  // a random walk of thrust and turn, an impulse now and then
    seek,    // chases another body seen in the snapshots (a waypoint when alone)
    orbit,   // circles a point of its own
    idle,    // zero input: the body only drifts
    hunter,  // Asteroids: turns to the nearest rock or ship, leads it, fires when lined up, shies from rocks
    game,    // the game's own bot (client_sim/game_bot.hpp), made by its definition; seek when it has none
};

// The --behavior flag: one kind for every bot, or `mixed`, a kind per bot by its index.
enum class behavior_choice : std::uint8_t { random, seek, orbit, idle, mixed, hunter, game };

std::optional<behavior_choice> parse_behavior(std::string_view name);
std::string_view to_string(behavior_kind kind);
// `mixed` cycles random, seek, orbit, idle, hunter over the bot indices.
behavior_kind resolve_behavior(behavior_choice choice, std::uint32_t index);

// What a behaviour sees on a tick.
struct observation {
    // The bot's own body as predicted for this tick; null until the first snapshot placed it.
    const world::body* own = nullptr;
};

class behavior {
public:
    behavior(behavior_kind kind, std::uint64_t seed, std::uint32_t index, const world::world_config& config);

    // The input for the next tick. Thrust and turn are finite and in [−1, 1].
    world::player_input next(const observation& seen);

    // A snapshot's bodies (increasing id order): seek follows its target in them.
    void observe(std::span<const protocol::BodyState> bodies, std::uint32_t own_id);

    [[nodiscard]] behavior_kind kind() const { return kind_; }
    // Seek: the body id it chases, 0 when none.
    [[nodiscard]] std::uint32_t target_id() const { return target_id_; }

private:
    world::player_input random_walk();
    world::player_input seek(const world::body& own);
    world::player_input orbit(const world::body& own);
    world::player_input hunt(const world::body& own);
    void observe_prey(std::span<const protocol::BodyState> bodies, std::uint32_t own_id);
    // Turn and thrust that head the body along `direction` (any length, non-zero).
    world::player_input steer(const world::body& own, const world::vec2& direction);
    world::vec2 random_point();

    behavior_kind kind_;
    world::world_config config_;  // boundary, size and control style: how to steer
    world::rng rng_;
    // random
    scenes::wandering_stick wander_;  // the random walk's stick
    // seek
    std::uint32_t target_id_ = 0;
    std::optional<world::vec2> target_;  // m, where the target was last seen (or the waypoint)
    bool target_is_waypoint_ = true;
    // hunter: the nearest body worth shooting in the last snapshot
    std::optional<world::vec2> prey_;  // m, where it was
    world::vec2 prey_velocity_{0, 0};  // m/s
    // orbit
    world::vec2 centre_{0, 0};  // m
    float radius_ = 0;          // m
};

}  // namespace arena::bots
