#pragma once
// One player's session with the server, with no socket and no clock: the one client core that
// the bots (client_core.hpp) and the browser SDK (web/sdk/core/c_api.cpp, in WebAssembly) both
// run. It verifies every frame the server sends, does the Welcome checks, keeps the shapes of
// the bodies in view, decodes delta snapshots with the server's codec and acknowledges them,
// takes the game events (a respawn of ours moves the own body), predicts the own body and the
// own shots with the server's world code (prediction.hpp), places the own bullets where the
// prediction has them, and paces the inputs (input_pacer.hpp). It encodes what the client
// sends: Hello, Input (numbered, with the delta acknowledgement), Ping and Bye.
//
// What is not here is its owner's: the bots add their behaviour, faults and figures; the
// browser adds interpolation and drawing (in TypeScript) and the inputs of the game.
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
#include "protocol/messages.hpp"
#include "protocol/shapes.hpp"
#include "server/world/config.hpp"
#include "server/world/result.hpp"

namespace arena::bots {

// One of the player's own bullets, where the prediction has it now (after the last input
// sent), as the own ship is drawn: a confirmed one (`body_id`, its body in the view) moved on
// from the newest snapshot, a predicted one the server has not shown yet (`body_id` 0) from
// its spawn. Drawn from the newest view, a bullet would appear a round trip and the
// interpolation delay behind the ship that fired it. 24 bytes (the C API hands them out as is).
struct own_bullet {
    std::uint32_t body_id = 0;
    std::uint32_t sequence = 0;  // the input that fired it
    float x = 0, y = 0;          // m
    float vx = 0, vy = 0;        // m/s
};

// Where a session gets a Welcome's world_config parsed: its own parse unless an owner shares
// one among many sessions (client_shared: 1000 bots parse it once).
class config_source {
public:
    // The config (never null), or why there is none.
    virtual result<const world::world_config*> config_for(const protocol::welcome_info& welcome) = 0;

protected:
    ~config_source() = default;
};

struct session_options {
    bool delta_snapshots = true;  // Hello.delta_snapshots
    bool spectator = false;       // Hello.spectator: no body, no inputs; full snapshots of the world
    // The transport carries messages that may be lost, duplicated or reordered (datagrams): a
    // Snapshot or Pong before the Welcome, or a Snapshot no newer than the last one, is dropped
    // (stale()), not a protocol error as on a stream.
    bool unordered = false;
    // A misbehaving bot: acknowledgements that make no sense to it (it flooded, or sent a NaN)
    // are not protocol errors, and its inputs are not paced.
    bool lenient = false;
};

class session {
public:
    enum class end_kind : std::uint8_t { none, by_server, protocol_error };

    // configs: null to parse each Welcome's world_config here; else kept by the owner.
    explicit session(session_options options = {}, config_source* configs = nullptr);

    // --- what the server sent -------------------------------------------------------------
    // Exactly one frame, length prefix included (one WebSocket message or datagram). Returns
    // the payload type once it is verified and handled, or Payload::NONE when it is refused
    // (the session ended: error() says why) or dropped (stale()). Reject and Bye end it too
    // (by the server) and return their type.
    protocol::Payload feed(std::span<const std::uint8_t> frame);
    // One whole frame that the owner cut from a stream with its frame_reader (8-byte aligned).
    protocol::Payload handle(std::span<const std::uint8_t> frame);
    // The last frame fed was dropped: a datagram that came stale (session_options::unordered).
    [[nodiscard]] bool stale() const { return stale_; }

    // --- what the client sends (each returns one frame, valid until the next call) ---------
    // `match` and `mode` (Hello.match, Hello.mode): the match to join, or the mode of one to join
    // or create; both empty, the server's default match.
    std::span<const std::uint8_t> hello(std::string_view name, std::string_view token, std::string_view match = {},
                                        std::string_view mode = {});
    // Numbers the input, predicts it (once a snapshot placed the body) and encodes it with
    // the newest delta view decoded as the acknowledgement. Empty before the Welcome, after
    // the end, and for a spectator (the server refuses its Inputs). Empty too for a tick the
    // pacing leaves out (protocol/README.md, "Input pacing"): the server kept too many of this
    // player's inputs waiting, so this tick's is neither numbered, predicted nor sent; the
    // next one carries the next sequence.
    std::span<const std::uint8_t> input(float thrust, float turn, std::uint8_t buttons);
    // Lag compensation (docs/LAG_COMPENSATION.md): the moment of the world this client shows
    // now, in 1/256 ticks (a renderer's interpolated tick; 0, the default: the newest snapshot's
    // tick, which is what a client that draws no interpolation shows). Every input carries it
    // (Input.view_tick and view_fraction), so the server judges its shots against that past.
    void set_view_moment(std::uint64_t moment) { view_moment_ = moment; }
    std::span<const std::uint8_t> ping(std::uint64_t client_time);
    std::span<const std::uint8_t> bye(std::string_view reason);
    // The frame the last of those calls returned.
    [[nodiscard]] std::span<const std::uint8_t> out() const { return out_; }

    // The same steps for an owner that encodes into a buffer of its own (the bots): whether
    // this tick's input goes out (the pacing), and the input numbered, predicted and ready to
    // encode, with the acknowledgement. Only once joined.
    bool send_this_tick();
    protocol::input_msg next_input(const world::player_input& input);

    // --- state ----------------------------------------------------------------------------
    [[nodiscard]] bool joined() const { return predictor_.has_value(); }
    [[nodiscard]] bool ended() const { return end_ != end_kind::none; }
    [[nodiscard]] end_kind how_ended() const { return end_; }
    [[nodiscard]] bool spectator() const { return options_.spectator; }
    [[nodiscard]] const std::string& error() const { return error_; }
    [[nodiscard]] std::uint32_t player_id() const { return player_id_; }
    // The own body: the Welcome's, then each respawn's.
    [[nodiscard]] std::uint32_t entity_id() const { return entity_id_; }
    [[nodiscard]] std::uint16_t tick_rate() const { return welcome_.tick_rate; }
    [[nodiscard]] std::uint16_t snapshot_rate() const { return welcome_.snapshot_rate; }
    // The Welcome as it came (world_config, statics and all); empty before it.
    [[nodiscard]] const protocol::welcome_info& welcome() const { return welcome_; }
    [[nodiscard]] const world::world_config* config() const { return config_; }
    // What ended it, when the server did: the Reject's code, or the Bye's result.
    [[nodiscard]] std::optional<protocol::RejectCode> reject_code() const { return reject_code_; }
    [[nodiscard]] const protocol::match_result& result() const { return result_; }
    // The client_time the newest Pong echoed.
    [[nodiscard]] std::uint64_t pong_time() const { return pong_time_; }
    // How long the server held that Ping before it read it (µs); none: the server did not say.
    [[nodiscard]] std::optional<std::uint32_t> pong_server_hold_us() const { return pong_server_hold_us_; }

    // The newest snapshot: its tick, ack and bodies (by increasing id; dequantised for a delta).
    [[nodiscard]] std::uint32_t view_tick() const { return view_tick_; }
    [[nodiscard]] std::uint32_t view_ack() const { return view_ack_; }
    // The newest Snapshot's tick, whether its view decoded or not (0 before one).
    [[nodiscard]] std::uint32_t last_tick() const { return last_tick_; }
    [[nodiscard]] const std::vector<protocol::BodyState>& view() const { return view_; }
    // Shapes of the newest view's bodies that this client holds, by id; the Welcome's statics.
    [[nodiscard]] const std::vector<protocol::shape_desc>& shapes() const { return shapes_; }
    [[nodiscard]] const std::vector<protocol::static_body>& statics() const { return welcome_.statics; }
    // The shape of body `id` (a static one from the Welcome, any other from the snapshots),
    // or null when this client does not hold it.
    [[nodiscard]] const protocol::shape_desc* shape_of(std::uint32_t id) const;

    // What the newest Snapshot brought, for an owner's figures: the shapes it described, its
    // game table (lines, names, events as sent; an event is taken once, by sequence: those of
    // game().events above events_taken_before(), each above the one taken before it), the size
    // of its delta (bytes; 0 for a full one), the prediction's correction and the own shots
    // matched with an error (spawn error, m).
    [[nodiscard]] const std::vector<protocol::shape_desc>& arrived() const { return arrived_; }
    [[nodiscard]] const protocol::game_list& game() const { return game_; }
    [[nodiscard]] std::uint32_t events_taken_before() const { return events_before_; }
    [[nodiscard]] bool was_delta() const { return was_delta_; }
    [[nodiscard]] std::size_t delta_bytes() const { return delta_bytes_; }
    [[nodiscard]] const predictor::correction& correction() const { return correction_; }
    [[nodiscard]] const std::vector<float>& shot_errors() const { return shot_errors_; }

    // Null before the Welcome.
    [[nodiscard]] const predictor* prediction() const { return predictor_ ? &*predictor_ : nullptr; }
    [[nodiscard]] const protocol::delta::receiver* deltas() const { return deltas_ ? &*deltas_ : nullptr; }
    // The own body as predicted for the last input sent; null before a snapshot placed it.
    [[nodiscard]] const world::body* predicted() const;
    // The own bullets (Asteroids: own_shots.hpp) where the prediction has them now, confirmed
    // ones by increasing body id, then predicted ones oldest first. A bullet flies free (no
    // drag, no gravity, no steering), so it is moved by the world's own integration, wrapping
    // included: bit for bit the server's flight until the bullet hits something.
    [[nodiscard]] std::vector<own_bullet> own_bullets() const;
    // The prediction error of the newest snapshot (m), when it measured one.
    [[nodiscard]] std::optional<float> prediction_error() const { return correction_.error; }
    [[nodiscard]] std::uint32_t last_sequence() const { return predictor_ ? predictor_->last_sequence() : 0; }
    // The newest ack_sequence that made sense (the newest input the server consumed).
    [[nodiscard]] std::uint32_t last_ack() const { return last_ack_; }
    // The tick the own body is predicted for, what the client shows of itself: the newest
    // snapshot's, one more for each input sent after the one it acknowledged.
    [[nodiscard]] std::uint32_t predicted_tick() const {
        const std::uint32_t sent = last_sequence();
        return last_tick_ + (sent > last_ack_ ? sent - last_ack_ : 0);
    }
    [[nodiscard]] std::uint32_t delta_ack() const { return deltas_ ? deltas_->ack() : 0; }
    // Why the newest Snapshot's delta did not decode (its view was skipped and the baselines
    // dropped, so the server sends a full one next); empty when it did. A server bug.
    [[nodiscard]] const std::string& delta_problem() const { return delta_problem_; }
    [[nodiscard]] std::uint64_t delta_failures() const { return delta_failures_; }
    // Ticks whose input the pacing left out.
    [[nodiscard]] std::uint64_t inputs_left_out() const { return pacer_.left_out(); }

private:
    protocol::Payload fail(std::string reason, end_kind kind = end_kind::protocol_error);
    protocol::Payload drop();
    protocol::Payload on_welcome(const protocol::Message& message);
    protocol::Payload on_snapshot(const protocol::Message& message);
    protocol::Payload on_reject(const protocol::Message& message);
    protocol::Payload on_bye(const protocol::Message& message);
    // Merges the shapes and takes the game a snapshot carries; false (ended) when malformed.
    bool take_shapes(const protocol::snapshot_view& snapshot);
    bool take_game(const protocol::snapshot_view& snapshot);
    // Sets the view from a snapshot; false when its delta did not decode (skipped).
    bool take_view(const protocol::snapshot_view& snapshot);
    void predict(const protocol::snapshot_view& snapshot);
    std::span<const std::uint8_t> keep(std::vector<std::uint8_t> frame);

    session_options options_;
    config_source* configs_;
    end_kind end_ = end_kind::none;
    bool stale_ = false;
    std::string error_;
    protocol::frame_reader frames_;
    std::vector<std::uint8_t> out_;

    protocol::welcome_info welcome_;
    std::optional<world::world_config> own_config_;  // parsed here when there is no config_source
    const world::world_config* config_ = nullptr;
    std::uint32_t player_id_ = 0;
    std::uint32_t entity_id_ = 0;
    std::optional<predictor> predictor_;
    std::optional<protocol::delta::receiver> deltas_;
    input_pacer pacer_;  // fed by each decoded snapshot, asked by each input
    std::uint32_t last_ack_ = 0;
    std::optional<protocol::RejectCode> reject_code_;
    protocol::match_result result_;
    std::uint64_t pong_time_ = 0;
    std::optional<std::uint32_t> pong_server_hold_us_;

    bool have_tick_ = false;
    std::uint32_t last_tick_ = 0;  // the newest Snapshot's, decoded or not
    std::uint32_t view_tick_ = 0;
    std::uint64_t view_moment_ = 0;  // set_view_moment's; 0: view_tick_
    std::uint32_t view_ack_ = 0;
    std::vector<protocol::BodyState> view_;
    std::vector<protocol::shape_desc> shapes_;
    std::vector<protocol::shape_desc> arrived_;
    protocol::game_list game_;
    std::uint32_t events_before_ = 0;  // last_event_ before the newest snapshot
    std::uint32_t last_event_ = 0;     // the sequence of the newest game event taken
    bool was_delta_ = false;
    std::size_t delta_bytes_ = 0;
    predictor::correction correction_;
    std::vector<float> shot_errors_;
    std::string delta_problem_;
    std::uint64_t delta_failures_ = 0;
};

}  // namespace arena::bots
