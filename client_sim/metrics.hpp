#pragma once
// Everything the bots measure, in one place that the fleet owns. The io_context runs on one
// thread, so plain counters suffice: no atomics, no locks.
#include <cstdint>
#include <map>
#include <string>

#include "client_sim/hit_registration.hpp"
#include "client_sim/own_shots.hpp"
#include "client_sim/stats.hpp"
#include "protocol/game.hpp"

namespace arena::bots {

// Occurrences by reason, in a fixed (sorted) order for the report.
using tally = std::map<std::string, std::uint64_t>;

// How one bot's run ended.
// One line of a scoreboard as a client saw it.
struct seen_line {
    std::string name;
    protocol::player_row row;
    std::vector<std::int32_t> values;  // the game's declared player fields, in its manifest's order
    bool operator==(const seen_line&) const = default;
};

struct bot_outcome {
    std::string name;  // the bot's Hello.name
    bool misbehaving = false;
    bool joined = false;
    bool ended = false;           // its connection is over
    bool ended_early = false;     // ... before the run ended
    bool protocol_error = false;  // the server sent something the protocol does not allow
    bool server_goodbye = false;  // the server ended it with Bye or Reject shutting_down: orderly
    std::string reason;           // why it ended; empty while it runs
    // The scoreboard this client saw at the end: the Bye's when the match's end reached it
    // (final_scoreboard), else the lines it held last. Empty under rules that keep no score.
    std::vector<seen_line> scoreboard;
    bool final_scoreboard = false;
    std::uint32_t winner = 0;  // the Bye's winner (0: nobody, or no Bye)
    // What the game declares of itself (the Welcome's manifest), its teams' declared values
    // (by team number, in the manifest's team_fields order) and the Bye's winning team.
    protocol::game_manifest game;
    std::map<std::uint8_t, std::vector<std::int32_t>> teams;
    std::uint8_t winning_team = 0;
    std::vector<std::uint32_t> winners;  // the Bye's winning players (several on a tie or a team)
    std::uint16_t tick_rate = 0;         // the Welcome's: a duration field in seconds

    // A well-behaved bot must join, keep its session until the run or the server ends it,
    // and never see a protocol error. Misbehaving bots are expected to be dropped and never
    // fail the run.
    [[nodiscard]] bool failed() const {
        if (misbehaving) return false;
        return !joined || protocol_error || (ended_early && !server_goodbye);
    }
};

struct fleet_metrics {
    // Whole run, every bot.
    std::uint64_t bytes_in = 0;
    std::uint64_t bytes_out = 0;
    std::uint64_t snapshots = 0;
    std::uint64_t inputs_sent = 0;
    std::uint64_t inputs_left_out =
        0;                            // ticks without an input: the server held more than one waiting (input_pacer.hpp)
    std::uint64_t ticks_skipped = 0;  // shared ticker ticks dropped because the process lagged
    std::uint64_t predictions_exact = 0;     // prediction errors exactly 0 (well-behaved bots)
    std::uint64_t snapshot_bytes = 0;        // frames of every snapshot received, bytes
    std::uint64_t view_bodies = 0;           // bodies those snapshots held
    std::uint64_t delta_snapshots = 0;       // snapshots that came as deltas (against a baseline or not)
    std::uint64_t delta_errors = 0;          // deltas that did not decode (a server bug; the bot recovers)
    std::uint64_t delta_payload_bytes = 0;   // the codec's bytes inside those deltas (no framing)
    std::uint64_t delta_bodies = 0;          // bodies the decoded deltas held
    std::uint64_t stale_messages = 0;        // on datagrams: snapshots duplicated or overtaken, dropped
    std::uint64_t shapes_received = 0;       // body shapes described by snapshots (statics of Welcomes apart)
    std::uint64_t shape_bytes = 0;           // their BodyShape and ShapeVertex bytes
    std::uint64_t game_bytes = 0;            // the game's lines, names and events in snapshots
    std::uint64_t game_events = 0;           // events taken (each once per client)
    std::uint64_t bodies_without_shape = 0;  // bodies in a decoded view whose shape the bot did not hold
    shot_counts own_shots;                   // predicted own shots, as matched (well-behaved bots, at the end)
    hit_counts hits;                         // hit registration (hit_registration.hpp; well-behaved bots, at the end)

    // The current second, for the progress line; rolled over by the fleet's reporter.
    std::uint64_t interval_bytes_in = 0;
    std::uint64_t interval_bytes_out = 0;
    std::uint64_t interval_snapshots = 0;
    sample_set interval_rtt_ms;
    sample_set interval_prediction_error_m;

    // Whole run, well-behaved bots only (a misbehaving bot's figures measure its fault).
    sample_set rtt_ms;  // Ping → Pong, ms
    // The same round trip split in two, where the Pong says how long the server held the Ping
    // (TCP: until its next tick's read): that hold, and the rest, the network's round trip.
    sample_set server_hold_ms;           // ms
    sample_set network_rtt_ms;           // ms: rtt_ms − server_hold_ms
    sample_set snapshot_gap_ms;          // between two snapshots of one bot, ms
    sample_set prediction_error_m;       // see prediction.hpp
    sample_set input_lag_ticks;          // inputs sent but not yet consumed, at each snapshot
    sample_set snapshots_per_s_per_bot;  // filled at the end, one value per bot
    sample_set bodies_in_view;           // per snapshot
    sample_set snapshot_bytes_each;      // per snapshot, its frame's bytes
    sample_set own_shot_error_m;         // spawn error of own shots matched with one, m (own_shots.hpp)
    // A ship lost to a bullet (Asteroids): how long before the news arrived the client showed
    // itself at the moment it was judged hit (that tick, less the shot's rewind), ms. See
    // docs/LAG_COMPENSATION.md, "What a victim sees".
    sample_set hit_after_seen_ms;

    // One value per second of the run, the whole fleet.
    sample_set snapshots_per_s;
    sample_set bytes_in_per_s;
    sample_set bytes_out_per_s;

    tally rejects;         // every Reject received: "code: reason"
    tally disconnects;     // every connection that ended before the run did, by reason
    tally delta_problems;  // why deltas did not decode
};

}  // namespace arena::bots
