#pragma once
// Client-side prediction of the bot's own body, as a game client does it, without sockets so
// that it is tested against a local "server" world.
//
// The predictor runs the server's own world code on a world that holds only this player's
// body. Each input is applied locally when it is sent; each snapshot resets the body to the
// server's state after input `ack_sequence`, drops the acknowledged inputs and replays the
// rest. With no other body near ours and the server consuming exactly our inputs, one per
// tick, the prediction is bit-exact: the world is float and the wire carries its floats
// unchanged (server/world/types.hpp).
//
// Under Asteroids rules the ship's own shots are predicted too (own_shots.hpp): an input that
// fires gives the predicted ship its recoil and spawns a predicted bullet, with the rules'
// code, and the server's bullet from the same input replaces it when its origin arrives.
//
// Prediction error, for input s: the distance between the position predicted for s when it
// was sent (what a player would have seen) and the position in the snapshot whose
// ack_sequence is s.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "client_sim/own_shots.hpp"
#include "protocol/arena_generated.h"
#include "server/world/input.hpp"
#include "server/world/world.hpp"

namespace arena::bots {

class predictor {
public:
    // server_config: the Welcome's world_config; entity_id and player_id: the Welcome's.
    predictor(const world::world_config& server_config, std::uint32_t entity_id, std::uint32_t player_id);

    // Input `sequence` (1, 2, ... without gaps) is being sent: predict its tick.
    void on_input(std::uint32_t sequence, const world::player_input& input);

    enum class ack_problem : std::uint8_t {
        none,
        went_back,  // ack_sequence below an earlier snapshot's: the server broke the protocol
        ahead,      // ack_sequence of an input never sent: the server broke the protocol
    };
    struct correction {
        bool own_found = false;      // the snapshot held our body
        std::optional<float> error;  // m, for input ack_sequence, when it was predicted
        std::uint32_t replayed = 0;  // unacknowledged inputs replayed on top
        ack_problem problem = ack_problem::none;
    };
    // The snapshot of `tick` arrived. own: our body's state in it, null when absent; view:
    // every body in it, by increasing id; origins: its shot origins (every player's).
    correction on_snapshot(std::uint32_t tick, std::uint32_t ack_sequence, const protocol::BodyState* own,
                           std::span<const protocol::BodyState> view = {},
                           std::span<const protocol::ShotOrigin> origins = {});
    // The own shots: those still predicted, and how the matching went.
    [[nodiscard]] const own_shots& shots() const { return shots_; }
    // Spawn errors (m) of the shots matched with an error since the last call.
    [[nodiscard]] std::vector<float> take_shot_errors() { return std::exchange(shot_errors_, {}); }

    // The body as predicted for the last input sent; null before a snapshot placed it.
    [[nodiscard]] const world::body* body() const;
    [[nodiscard]] std::size_t unacknowledged() const { return pending_.size(); }
    [[nodiscard]] std::uint32_t last_sequence() const { return last_sequence_; }
    [[nodiscard]] std::uint64_t dropped_inputs() const { return dropped_; }

    // The config of the local world: the server's without rocks, and with a cheaper but
    // equivalent broadphase for a lone body (see prediction.cpp).
    static world::world_config local_config(const world::world_config& server_config);

    // Inputs kept while unacknowledged; beyond this the oldest are forgotten (their
    // prediction error is then not measured). 512 ticks = 8.5 s at 60 Hz.
    static constexpr std::size_t max_pending = 512;

private:
    struct pending_input {
        std::uint32_t sequence = 0;
        world::player_input input{};
        bool predicted = false;      // sent after the body was placed: `position` is meaningful
        world::vec2 position{0, 0};  // m, as predicted when sent
    };

    void step(world::world& w, const world::player_input& input);
    // Steps predicted_ with input `sequence`, firing (a predicted shot) when the rules would.
    void step_predicted(std::uint32_t sequence, const world::player_input& input);
    void place_body(const protocol::BodyState& own);
    void set_state(world::world& w, const protocol::BodyState& own);
    // The pending input with this sequence, or null.
    const pending_input* find(std::uint32_t sequence) const;
    void drop_through(std::uint32_t sequence);

    world::world_config config_;
    std::uint32_t entity_id_;
    std::uint32_t player_id_;
    // acked_: the world after input acked_sequence_, i.e. the server's last state, carried
    // forward by our own steps between snapshots so that it keeps the world's hidden state
    // (contact warm-start impulses, impulse cooldown) that snapshots do not carry.
    world::world acked_;
    // predicted_: acked_ plus every unacknowledged input; what the player sees.
    world::world predicted_;
    bool placed_ = false;
    std::uint32_t acked_sequence_ = 0;
    std::uint32_t last_sequence_ = 0;
    std::uint64_t dropped_ = 0;
    // Unacknowledged inputs in sequence order. A vector used as a queue: drop_through erases
    // from the front, a few elements; no allocation once it reached its working size.
    std::vector<pending_input> pending_;
    world::tick_inputs inputs_;  // reused for every step: one element, our body
    own_shots shots_;
    own_shots::gun gun_;  // predicted_'s
    // The last snapshot held our ship: a dead one (respawning) fires nothing.
    bool alive_ = false;
    std::vector<float> shot_errors_;
};

}  // namespace arena::bots
