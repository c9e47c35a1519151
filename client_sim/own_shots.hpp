#pragma once
// The player's own shots, predicted as the ship is: when an input with a fire button is
// stepped, the client decides with the game's own fire rule (server/rules/shot_rule.hpp, from
// the game's definition: Asteroids' is games/asteroids/asteroids_shot.hpp) whether the ship may
// fire, spawns the bullet and gives the ship its recoil. Each
// predicted shot waits for the server's bullet from the same input (protocol ShotOrigin,
// matched by input sequence) and is then replaced by it: exactly when the two spawns are bit
// for bit equal, with an error (m) otherwise. A shot still unmatched once a snapshot
// acknowledged its input never happened on the server (the server sends the origin in the
// first snapshot that holds the bullet, and every snapshot acknowledging the input holds it
// unless it is already gone): it is dropped, as unconfirmed.
//
// The gun's state (cooldown and live bullets) counts in input sequences, one input a tick,
// as the server counts it in ticks. After each snapshot it is rebuilt from what the server
// confirmed: the newest confirmed shot's cooldown, and the confirmed bullets still in view.
// The server's ticks and the inputs drift apart whenever an input comes late (the world
// repeats the last one: an underrun) or is dropped, so each confirmed shot keeps the tick it
// was fired in, and the gun is rebuilt in the sequences of the newest snapshot's tick and
// acknowledgement: without it, one late input put every later shot's cooldown and every
// bullet's lifetime a tick off until the bullet was gone.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "protocol/arena_generated.h"
#include "server/rules/shot_rule.hpp"
#include "server/world/config.hpp"
#include "server/world/input.hpp"

namespace arena::bots {

// A shot as the client predicted it, waiting for the server's.
struct predicted_shot {
    std::uint32_t sequence = 0;  // the input that fired it
    world::vec2 position{0, 0};  // m, spawn
    world::vec2 velocity{0, 0};  // m/s, spawn
};

// What the matching found (each shot counted once).
struct shot_counts {
    std::uint64_t exact = 0;        // the server's spawn equals the prediction bit for bit
    std::uint64_t with_error = 0;   // matched, but the spawns differ
    std::uint64_t unconfirmed = 0;  // predicted, the server never fired it
    std::uint64_t unpredicted = 0;  // the server's, with no prediction from its input
};

class own_shots {
public:
    // Predicts nothing unless `config` plays a game whose definition has a fire rule for its
    // rules_params.
    own_shots(const world::world_config& config, std::uint32_t player_id);

    // The gun: the cooldown's end and the live bullets' firing inputs.
    struct gun {
        std::uint32_t next_fire = 0;
        std::vector<std::uint32_t> live;
    };

    // Input `sequence` is being stepped on `ship` from `g`: when the rules would fire, gives the
    // ship its recoil, updates `g` and returns the shot.
    std::optional<predicted_shot> fire(gun& g, std::uint32_t sequence, const world::player_input& input,
                                       world::body& ship) const;
    // A bullet of ours the server confirmed, still in the newest view.
    struct confirmed_shot {
        std::uint32_t body_id = 0;
        std::uint32_t sequence = 0;
        std::int64_t tick = 0;  // the server's tick it was fired in, as the confirming snapshot tells
    };

    // A shot predicted for the input just sent, or on a replay of an unacknowledged one.
    void predicted(const predicted_shot& shot) { waiting_.push_back(shot); }
    // Before a replay: the unacknowledged inputs' shots are predicted again.
    void forget_after(std::uint32_t sequence);

    // The snapshot of `tick` acknowledging input `ack`: this player's `origins` are matched;
    // waiting shots of inputs up to `ack` without one are dropped; `view` (by increasing id)
    // tells which confirmed bullets are still there. Returns the gun after input `ack`. The
    // spawn errors (m) of shots matched with one go to `errors`.
    gun on_snapshot(std::uint32_t tick, std::uint32_t ack, std::span<const protocol::ShotOrigin> origins,
                    std::span<const protocol::BodyState> view, const world::world_config& config,
                    std::vector<float>& errors);

    [[nodiscard]] bool enabled() const { return rule_ != nullptr; }
    [[nodiscard]] const shot_counts& counts() const { return counts_; }
    // Predicted shots the server has not confirmed yet, oldest first.
    [[nodiscard]] std::span<const predicted_shot> waiting() const { return waiting_; }
    // Confirmed bullets still in the newest view, by the order they were confirmed.
    [[nodiscard]] std::span<const confirmed_shot> confirmed() const { return confirmed_; }
    // The fire rule, with the server's parameters (its config's rules_params); null: disabled.
    [[nodiscard]] const rules::shot_rule* rule() const { return rule_.get(); }

private:
    std::unique_ptr<rules::shot_rule> rule_;
    std::uint32_t player_id_;
    std::vector<predicted_shot> waiting_;
    std::vector<confirmed_shot> confirmed_;        // the server's bullets of ours, seen alive in the last view
    std::optional<std::uint32_t> last_confirmed_;  // the newest confirmed shot's input
    std::int64_t last_confirmed_tick_ = 0;         // and the tick it was fired in
    shot_counts counts_;
};

}  // namespace arena::bots
