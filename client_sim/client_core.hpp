#pragma once
// One simulated player with no sockets and no clock: the Welcome checks, client-side
// prediction and reconciliation, the delta receiver and its acks, the behaviour, the faults
// and the figures. It takes the server's bytes (or whole frames) and the time, and gives the
// bytes to send; its owner moves them. arena-bots runs it over TCP (bot.cpp), the tests over
// a simulated network in virtual time (tests/simnet/), and it builds for WebAssembly: plain
// C++20 over the world and protocol libraries, nothing else.
//
// The owner drives it: launch() when it starts connecting, connected() once the transport is
// up, then bytes or frames as they come, on_tick() once per server tick, finish() at the end.
// After every call the owner looks at output() (frames to send, in order), closing() (close
// once the output is written, then call flushed()) and ended() (close now).
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "client_sim/behavior.hpp"
#include "client_sim/client_shared.hpp"
#include "client_sim/input_pacer.hpp"
#include "client_sim/metrics.hpp"
#include "client_sim/misbehave.hpp"
#include "client_sim/prediction.hpp"
#include "protocol/delta/receiver.hpp"
#include "protocol/framing.hpp"
#include "server/world/rng.hpp"

namespace arena::bots {

// Nanoseconds since an origin the owner picks (the run's start, or a virtual clock's zero).
// The core only subtracts two of them and echoes them in Pings.
using time_ns = std::uint64_t;

struct client_params {
    std::uint32_t index = 0;  // with seed: the behaviour's and the fault's random streams
    behavior_kind kind = behavior_kind::random;
    misbehavior mode = misbehavior::none;
    std::uint64_t seed = 1;
    std::string name;   // Hello.name
    std::string token;  // Hello.token
    bool delta_snapshots = true;
    time_ns join_timeout = 10'000'000'000;  // ns from launch() to Welcome before giving up
    // The transport carries messages that may be lost, duplicated or reordered (datagrams):
    // a Snapshot or Pong before the Welcome, or a Snapshot no newer than the last one, is
    // dropped (and counted), not a protocol error as it is on a stream.
    bool unordered = false;
};

class client_core {
public:
    enum class phase : std::uint8_t { idle, connecting, joining, playing, ended };
    enum class end_kind : std::uint8_t { orderly, by_server, protocol_error, transport_error };

    client_core(client_shared& shared, client_params params);
    client_core(const client_core&) = delete;
    client_core& operator=(const client_core&) = delete;

    // --- the transport ------------------------------------------------------------------
    // Connecting starts now: the join timeout runs from here.
    void launch(time_ns now);
    // The transport is up: queues the Hello.
    void connected();
    // Bytes of the server's stream, split anywhere: frames are handled as they complete.
    void on_bytes(std::span<const std::uint8_t> bytes, time_ns now);
    // Exactly one frame, length prefix included (a message transport).
    void on_frame(std::span<const std::uint8_t> frame, time_ns now);
    // The transport ended the session (the server closed, a read or write failed).
    void on_transport_end(end_kind kind, const std::string& reason) { end(kind, reason); }
    // Everything output() held was written; a closing core ends now.
    void flushed();

    // Frames to send, in order. The owner moves them out (swap with an empty vector keeps
    // both buffers' capacity) and counts them sent.
    [[nodiscard]] std::vector<std::uint8_t>& output() { return pending_; }
    // Close once the output is written (after a Bye, or an abrupt-close fault).
    [[nodiscard]] bool closing() const { return close_after_flush_; }
    // False once the slow-reader fault is on: the transport stops reading the server.
    [[nodiscard]] bool reading() const {
        return !(params_.mode == misbehavior::slow_reader && phase_ == phase::playing);
    }

    // --- the driver ---------------------------------------------------------------------
    // One server tick passed: this tick's input, and a Ping once a second.
    void on_tick(std::uint64_t tick, time_ns now);
    // The run is over: say Bye, close once it is written.
    void finish();
    // Ends the session now, with this reason.
    void abort(const std::string& reason) { end(end_kind::transport_error, reason); }
    // Gives up when no Welcome came within the join timeout.
    void check_join_timeout(time_ns now);

    // --- what it saw --------------------------------------------------------------------
    [[nodiscard]] phase current() const { return phase_; }
    [[nodiscard]] bool ended() const { return phase_ == phase::ended; }
    [[nodiscard]] const bot_outcome& outcome() const { return outcome_; }
    [[nodiscard]] std::uint32_t player_id() const { return player_id_; }
    [[nodiscard]] std::uint32_t entity_id() const { return entity_id_; }
    [[nodiscard]] std::uint64_t snapshots() const { return snapshots_; }
    // Null before the Welcome.
    [[nodiscard]] const predictor* prediction() const { return predictor_ ? &*predictor_ : nullptr; }
    [[nodiscard]] const protocol::delta::receiver* deltas() const { return deltas_ ? &*deltas_ : nullptr; }
    // The shape of body `id` (a static one from the Welcome, any other from the snapshots),
    // or null when this client does not hold it. Held while the body is in the newest view.
    [[nodiscard]] const protocol::shape_desc* shape_of(std::uint32_t id) const;
    [[nodiscard]] const std::vector<protocol::static_body>& statics() const { return statics_; }
    // The game (protocol/README.md, "Players and game events"): every player's line as of the
    // newest snapshot applied, by player id; a player's name ("" before it came); the events
    // taken, oldest first (the newest max_kept_events); the Bye's result once the match ended.
    [[nodiscard]] const std::map<std::uint32_t, protocol::player_row>& players() const { return players_; }
    [[nodiscard]] std::string player_name(std::uint32_t player) const;
    [[nodiscard]] const std::deque<protocol::game_event>& events() const { return events_; }
    [[nodiscard]] const protocol::match_result& result() const { return result_; }
    static constexpr std::size_t max_kept_events = 256;
    // The last snapshot's ack_sequence (the newest input the server consumed), 0 before one.
    [[nodiscard]] std::uint32_t last_ack() const { return last_ack_; }
    // The tick of the newest snapshot applied (0 before one).
    [[nodiscard]] std::uint32_t last_snapshot_tick() const { return last_snapshot_tick_; }
    // Figures that need the whole run (this core's snapshot rate) into the metrics.
    void add_final_figures(fleet_metrics& metrics) const;

private:
    void handle_frame(std::span<const std::uint8_t> frame, time_ns now);
    void on_welcome(const protocol::Message& message);
    void on_snapshot(const protocol::Message& message, time_ns now);
    void on_pong(const protocol::Message& message, time_ns now);
    void on_reject(const protocol::Message& message);
    void on_bye(const protocol::Message& message);
    // Keeps the shapes a snapshot describes; false (the session ended) when they are malformed.
    bool take_shapes(const protocol::snapshot_view& snapshot);
    // Keeps the lines, names and events a snapshot carries; false (ended) when malformed.
    bool take_game(const protocol::snapshot_view& snapshot);
    // The scoreboard this client holds, into the outcome (at the end).
    void record_scoreboard();
    // The newest view is `bodies`: drops the shapes of bodies not in it, counts those without one.
    void check_shapes(std::span<const protocol::BodyState> bodies);

    void send_input(const world::player_input& input);
    // Does this core's fault once it is due; true when it replaces this tick's input.
    bool misbehave();
    void queue(std::span<const std::uint8_t> bytes);
    // Records the outcome (first call only); the owner closes the transport.
    void end(end_kind kind, const std::string& reason);

    client_shared& shared_;
    client_params params_;
    phase phase_ = phase::idle;
    bot_outcome outcome_;

    protocol::frame_reader frames_;
    std::vector<std::uint8_t> pending_;  // frames waiting for the transport
    bool close_after_flush_ = false;
    std::string close_reason_;

    // From the Welcome.
    std::uint32_t player_id_ = 0;
    std::uint32_t entity_id_ = 0;
    std::uint16_t tick_rate_ = 0;
    std::optional<predictor> predictor_;
    std::optional<behavior> behavior_;
    std::optional<protocol::delta::receiver> deltas_;  // when the core asked for delta snapshots
    std::vector<protocol::BodyState> decoded_;         // the last delta's view as BodyState
    std::vector<protocol::static_body> statics_;       // the Welcome's, by increasing id
    std::vector<protocol::shape_desc> shapes_;         // the other bodies' of the newest view, by id
    std::vector<protocol::shape_desc> arrived_;        // a snapshot's descriptions, being merged
    std::size_t message_bytes_ = 0;                    // the frame being handled, prefix included
    std::uint32_t last_ack_ = 0;
    std::map<std::uint32_t, protocol::player_row> players_;  // by player id
    std::map<std::uint32_t, std::string> names_;             // by player id
    std::deque<protocol::game_event> events_;
    std::uint32_t last_event_ = 0;  // the sequence of the newest event taken
    protocol::game_list game_;      // a snapshot's, being read
    protocol::match_result result_;
    std::uint32_t last_snapshot_tick_ = 0;
    std::deque<protocol::earlier_input> recent_inputs_;  // datagrams: repeated in the next Inputs

    world::rng fault_rng_;  // garbage bytes, from the seed and index
    std::uint32_t ticks_played_ = 0;
    input_pacer pacer_;  // leaves out an input when the server keeps too many waiting
    bool fault_done_ = false;

    time_ns launched_at_ = 0;
    time_ns first_snapshot_at_ = 0;
    time_ns last_snapshot_at_ = 0;
    std::uint64_t snapshots_ = 0;
};

}  // namespace arena::bots
