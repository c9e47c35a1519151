#pragma once
// One simulated player with no sockets and no clock: the session with the server (session.hpp:
// the Welcome checks, the shapes, the delta receiver and its acks, prediction and
// reconciliation, input pacing; the browser SDK runs the same code), and around it the
// behaviour, the faults and the figures. It takes the server's bytes (or whole frames) and
// the time, and gives the bytes to send; its owner moves them. arena-bots runs it over TCP
// (bot.cpp), the tests over a simulated network in virtual time (tests/simnet/), and it
// builds for WebAssembly: plain C++20 over the world and protocol libraries, nothing else.
//
// The owner drives it: launch() when it starts connecting, connected() once the transport is
// up, then bytes or frames as they come, on_tick() once per server tick, finish() at the end.
// After every call the owner looks at output() (frames to send, in order), closing() (close
// once the output is written, then call flushed()) and ended() (close now).
#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "client_sim/behavior.hpp"
#include "client_sim/client_shared.hpp"
#include "client_sim/game_bot.hpp"
#include "client_sim/hit_registration.hpp"
#include "client_sim/metrics.hpp"
#include "client_sim/misbehave.hpp"
#include "client_sim/prediction.hpp"
#include "client_sim/session.hpp"
#include "client_sim/shown_view.hpp"
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
    std::string join_match;                 // Hello.match
    std::string join_mode;                  // Hello.mode
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
    [[nodiscard]] std::uint32_t player_id() const { return session_.player_id(); }
    [[nodiscard]] std::uint32_t entity_id() const { return session_.entity_id(); }
    [[nodiscard]] std::uint64_t snapshots() const { return snapshots_; }
    // Null before the Welcome.
    [[nodiscard]] const predictor* prediction() const { return session_.prediction(); }
    [[nodiscard]] const protocol::delta::receiver* deltas() const { return session_.deltas(); }
    // The shape of body `id` (a static one from the Welcome, any other from the snapshots),
    // or null when this client does not hold it. Held while the body is in the newest view.
    [[nodiscard]] const protocol::shape_desc* shape_of(std::uint32_t id) const { return session_.shape_of(id); }
    [[nodiscard]] const std::vector<protocol::static_body>& statics() const { return session_.statics(); }
    // The session with the server, which this player drives.
    [[nodiscard]] const session& server_session() const { return session_; }
    // The game (protocol/README.md, "Players and game events"): every player's line as of the
    // newest snapshot applied, by player id; a player's name ("" before it came); the events
    // taken, oldest first (the newest max_kept_events); the Bye's result once the match ended.
    [[nodiscard]] const std::map<std::uint32_t, protocol::player_row>& players() const { return players_; }
    [[nodiscard]] std::string player_name(std::uint32_t player) const;
    [[nodiscard]] const std::deque<protocol::game_event>& events() const { return events_; }
    [[nodiscard]] const protocol::match_result& result() const { return session_.result(); }
    static constexpr std::size_t max_kept_events = 256;
    // The game's declared state (protocol/README.md, "Game manifest"): its manifest from the
    // Welcome, each player's and each team's values as of the newest snapshot applied (in the
    // manifest's field order), and its events taken, oldest first (the newest max_kept_events).
    using declared_values = std::array<std::int32_t, protocol::max_game_fields>;
    [[nodiscard]] const protocol::game_manifest& manifest() const { return session_.welcome().game; }
    [[nodiscard]] const std::map<std::uint32_t, declared_values>& player_values() const { return player_values_; }
    [[nodiscard]] const std::map<std::uint8_t, declared_values>& team_values() const { return team_values_; }
    [[nodiscard]] const std::deque<protocol::event_record>& records() const { return records_; }
    // The last snapshot's ack_sequence (the newest input the server consumed), 0 before one.
    [[nodiscard]] std::uint32_t last_ack() const { return session_.last_ack(); }
    // The tick of the newest snapshot applied (0 before one).
    [[nodiscard]] std::uint32_t last_snapshot_tick() const { return session_.last_tick(); }
    // Hit registration (hit_registration.hpp): the hits this player saw and the server's
    // verdicts; Asteroids only, well-behaved players only, settled when the session ends.
    [[nodiscard]] const hit_counts& hits() const { return hits_.counts(); }
    // Figures that need the whole run (this core's snapshot rate) into the metrics.
    void add_final_figures(fleet_metrics& metrics) const;

private:
    // The session took a frame (`handled`, NONE when refused or dropped): what follows for
    // this player, its figures and its end.
    void after_frame(protocol::Payload handled, std::size_t frame_bytes, time_ns now);
    void on_welcome();
    void on_snapshot(std::size_t frame_bytes, time_ns now);
    void on_pong(time_ns now);
    // Keeps the lines, names and events the newest snapshot carried.
    void take_game();
    // This player's ship was destroyed by a bullet (the event `lost`): how long ago it showed
    // itself where it was hit, into the fleet's hit_after_seen_ms.
    void lost_to_shot(const protocol::game_event& lost);
    // The rewind (1/256 ticks) the input `sequence` carried: how far behind it showed the others.
    void remember_rewind(std::uint32_t sequence, std::uint32_t rewind);
    [[nodiscard]] std::uint32_t rewind_of(std::uint32_t sequence) const;
    // What a game's own bot sees now.
    [[nodiscard]] game_view seen_by_game_bot() const;
    // The scoreboard this client holds, into the outcome (at the end).
    void record_scoreboard();
    // Counts the newest view's bodies this client holds no shape for.
    void check_shapes(std::span<const protocol::BodyState> bodies);

    // Claims the hits the own bullets make now on the targets of the newest view.
    void claim_hits();
    // A ship that respawned within the last invulnerable span (no target on the server).
    [[nodiscard]] bool invulnerable(std::uint32_t ship, std::uint32_t tick) const;
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

    session session_;
    protocol::frame_reader frames_;      // a stream's bytes into frames (on_bytes)
    std::vector<std::uint8_t> pending_;  // frames waiting for the transport
    bool close_after_flush_ = false;
    std::string close_reason_;

    std::optional<behavior> behavior_;                       // from the Welcome
    std::unique_ptr<game_bot> game_bot_;                     // --behavior game: the game's own, if it has one
    std::map<std::uint32_t, protocol::player_row> players_;  // by player id
    std::map<std::uint32_t, std::string> names_;             // by player id
    std::deque<protocol::game_event> events_;
    std::map<std::uint32_t, declared_values> player_values_;  // by player id
    std::map<std::uint8_t, declared_values> team_values_;     // by team number
    std::deque<protocol::event_record> records_;
    std::uint32_t last_record_ = 0;  // the newest record's sequence taken

    // Datagrams: the newest inputs sent, oldest first, repeated in the next Inputs.
    std::array<protocol::earlier_input, protocol::max_earlier_inputs> recent_inputs_{};
    std::size_t recent_count_ = 0;

    bool judge_hits_ = false;  // Asteroids, well-behaved
    hit_registration hits_;
    std::uint32_t first_view_tick_ = 0;
    std::map<std::uint32_t, std::uint32_t> respawned_;  // ship body id -> tick of its respawn
    // Asteroids' default span of a new ship's invulnerability (asteroids_params::invulnerable_ticks: 2 s).
    [[nodiscard]] std::uint32_t invulnerable_ticks() const { return 2u * session_.tick_rate(); }
    shown_view shown_;  // what it shows of the others (Asteroids bots: judge_hits_)
    std::deque<std::pair<std::uint32_t, std::uint32_t>> rewinds_;  // (input sequence, its view's rewind), oldest first
    std::map<std::uint32_t, std::uint32_t> rewound_hits_;  // own ship body id -> the rewind it was hit at (1/256 ticks)

    world::rng fault_rng_;  // garbage bytes, from the seed and index
    std::uint32_t ticks_played_ = 0;
    bool fault_done_ = false;

    time_ns launched_at_ = 0;
    time_ns first_snapshot_at_ = 0;
    time_ns last_snapshot_at_ = 0;
    std::uint64_t snapshots_ = 0;
};

}  // namespace arena::bots
