#pragma once
// The browser client's core: one player's session with no socket and no clock, for the
// TypeScript SDK to drive through the C API (c_api.cpp). It verifies every frame the server
// sends (the npm FlatBuffers runtime has no verifier), does the Welcome checks, decodes delta
// snapshots with the server's codec, keeps the shapes of the bodies in view, and predicts the
// player's own body with the server's world code (client_sim/prediction.hpp). It encodes what
// the client sends: Hello, Input (numbered, with the delta acknowledgement), Ping and Bye, and
// paces the Inputs as the bots do (client_sim/input_pacer.hpp).
//
// Unlike client_sim's client_core (a bot: its inputs come from a behaviour, its figures go to
// a fleet), the inputs here come from the game, and the decoded view is kept for it to draw.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "client_sim/input_pacer.hpp"
#include "client_sim/prediction.hpp"
#include "protocol/arena_generated.h"
#include "protocol/delta/receiver.hpp"
#include "protocol/framing.hpp"
#include "protocol/game.hpp"
#include "protocol/shapes.hpp"
#include "server/world/config.hpp"

namespace arena::sdk {

// One of the player's own bullets, where the prediction has it now (after the last input
// sent), as the own ship is drawn: a confirmed one (`body_id`, its body in the view) moved on
// from the newest snapshot, a predicted one the server has not shown yet (`body_id` 0) from
// its spawn. Drawn from the newest view, a bullet would appear a round trip and the
// interpolation delay behind the ship that fired it.
struct own_bullet {
    std::uint32_t body_id = 0;
    std::uint32_t sequence = 0;  // the input that fired it
    float x = 0, y = 0;          // m
    float vx = 0, vy = 0;        // m/s
};

class session {
public:
    // delta_snapshots: ask for delta snapshots (Hello.delta_snapshots). spectator: join to
    // watch (Hello.spectator): no body, no inputs; the server sends full snapshots of the
    // whole world.
    explicit session(bool delta_snapshots = true, bool spectator = false);

    // --- what the server sent -------------------------------------------------------------
    // Exactly one frame, length prefix included (one WebSocket message). Returns the message's
    // payload type once it is verified and handled, or Payload::NONE when it is refused: the
    // session has then ended and error() says why. Reject and Bye end it too (orderly).
    protocol::Payload feed(std::span<const std::uint8_t> frame);

    // --- what the client sends (each returns one frame, valid until the next call) ---------
    std::span<const std::uint8_t> hello(std::string_view name, std::string_view token);
    // Numbers the input, predicts it (once a snapshot placed the body) and encodes it with
    // the newest delta view decoded as the acknowledgement. Empty before the Welcome, and for
    // a spectator (the server refuses its Inputs). Empty too for a tick the pacing leaves out
    // (protocol/README.md, "Input pacing"): the server kept too many of this player's inputs
    // waiting, so this tick's is neither numbered, predicted nor sent; the next one carries
    // the next sequence.
    std::span<const std::uint8_t> input(float thrust, float turn, std::uint8_t buttons);
    std::span<const std::uint8_t> ping(std::uint64_t client_time);
    std::span<const std::uint8_t> bye(std::string_view reason);
    // The frame the last of those calls returned.
    [[nodiscard]] std::span<const std::uint8_t> out() const { return out_; }

    // --- state ----------------------------------------------------------------------------
    [[nodiscard]] bool joined() const { return predictor_.has_value(); }
    [[nodiscard]] bool ended() const { return ended_; }
    [[nodiscard]] bool spectator() const { return spectator_; }
    [[nodiscard]] const std::string& error() const { return error_; }
    [[nodiscard]] std::uint32_t player_id() const { return player_id_; }
    [[nodiscard]] std::uint32_t entity_id() const { return entity_id_; }
    [[nodiscard]] std::uint16_t tick_rate() const { return tick_rate_; }
    [[nodiscard]] std::uint16_t snapshot_rate() const { return snapshot_rate_; }
    [[nodiscard]] const world::world_config* config() const { return config_ ? &*config_ : nullptr; }

    // The newest snapshot: its tick, ack and bodies (by increasing id; dequantised for a delta).
    [[nodiscard]] std::uint32_t view_tick() const { return view_tick_; }
    [[nodiscard]] std::uint32_t view_ack() const { return view_ack_; }
    [[nodiscard]] const std::vector<protocol::BodyState>& view() const { return view_; }
    // Shapes of the newest view's bodies that this client holds, by id; the Welcome's statics.
    [[nodiscard]] const std::vector<protocol::shape_desc>& shapes() const { return shapes_; }
    [[nodiscard]] const std::vector<protocol::static_body>& statics() const { return statics_; }
    // The own body as predicted for the last input sent; null before a snapshot placed it.
    [[nodiscard]] const world::body* predicted() const;
    // The own bullets (Asteroids: own_shots.hpp) where the prediction has them now, confirmed
    // ones by increasing body id, then predicted ones oldest first. A bullet flies free (no
    // drag, no gravity, no steering), so it is moved by the world's own integration, wrapping
    // included: bit for bit the server's flight until the bullet hits something.
    [[nodiscard]] std::vector<own_bullet> own_bullets() const;
    // The prediction error of the newest snapshot (m), when it measured one.
    [[nodiscard]] std::optional<float> prediction_error() const { return prediction_error_; }
    [[nodiscard]] std::uint32_t last_sequence() const { return predictor_ ? predictor_->last_sequence() : 0; }
    [[nodiscard]] std::uint32_t delta_ack() const { return deltas_ ? deltas_->ack() : 0; }
    // Why the newest Snapshot's delta did not decode (its view was skipped and the baselines
    // dropped, so the server sends a full one next); empty when it did. A server bug.
    [[nodiscard]] const std::string& delta_problem() const { return delta_problem_; }
    [[nodiscard]] std::uint64_t delta_failures() const { return delta_failures_; }
    // Ticks whose input the pacing left out (input() returned an empty frame for them).
    [[nodiscard]] std::uint64_t inputs_left_out() const { return pacer_.left_out(); }

private:
    protocol::Payload fail(std::string reason);
    protocol::Payload on_welcome(const protocol::Message& message);
    protocol::Payload on_snapshot(const protocol::Message& message);
    std::span<const std::uint8_t> keep(std::vector<std::uint8_t> frame);

    bool delta_snapshots_;
    bool spectator_;
    bool ended_ = false;
    std::string error_;
    protocol::frame_reader frames_;
    std::vector<std::uint8_t> out_;

    std::uint32_t player_id_ = 0;
    std::uint32_t entity_id_ = 0;   // the own body: the Welcome's, then each respawn's
    std::uint32_t last_event_ = 0;  // the sequence of the newest game event taken
    protocol::game_list game_;      // a snapshot's, being read
    std::uint16_t tick_rate_ = 0;
    std::uint16_t snapshot_rate_ = 0;
    std::optional<world::world_config> config_;
    std::optional<bots::predictor> predictor_;
    std::optional<protocol::delta::receiver> deltas_;
    bots::input_pacer pacer_;  // fed by each decoded snapshot, asked by each input()

    std::uint32_t view_tick_ = 0;
    std::uint32_t view_ack_ = 0;
    bool have_view_ = false;
    std::vector<protocol::BodyState> view_;
    std::vector<protocol::shape_desc> shapes_;
    std::vector<protocol::shape_desc> arrived_;
    std::vector<protocol::static_body> statics_;
    std::optional<float> prediction_error_;
    std::string delta_problem_;
    std::uint64_t delta_failures_ = 0;
};

}  // namespace arena::sdk
