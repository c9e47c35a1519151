#pragma once
// What arena-bots prints: a progress line each second, and at the end a summary table (and
// the same as JSON). Built from fleet_metrics and the bots' outcomes; no sockets here.
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "client_sim/metrics.hpp"

namespace arena::bots {

// The failure a run reports when bots played but no prediction was ever measured.
inline constexpr const char* no_prediction_samples =
    "no prediction samples: bots played, but no snapshot confirmed a prediction";

struct final_report {
    double seconds = 0;  // wall time of the run
    std::uint32_t bots = 0;
    std::uint32_t joined = 0;
    std::uint32_t failed = 0;       // well-behaved bots that did not join, or lost their session
    std::uint32_t ended_early = 0;  // well-behaved sessions that ended before the run (any reason)
    std::uint32_t misbehaving = 0;
    std::uint32_t misbehaving_dropped = 0;  // misbehaving bots whose session the server ended
    std::uint64_t bytes_in = 0;
    std::uint64_t bytes_out = 0;
    std::uint64_t snapshots = 0;
    std::uint64_t inputs_sent = 0;
    std::uint64_t inputs_left_out = 0;  // input_pacer.hpp
    std::uint64_t ticks_skipped = 0;
    double prediction_exact_share = 0;  // [0, 1] of the measured predictions, bit-exact
    // Own shots (Asteroids, own_shots.hpp): how the predicted ones matched the server's, and the
    // share of matched ones whose spawn was bit-exact ([0, 1]; 0 when none matched).
    shot_counts own_shots;
    // Hit registration (hit_registration.hpp): hits the bots saw, those the server confirmed,
    // and the server's hits by them that they never saw.
    hit_counts hits;
    double own_shot_exact_share = 0;
    std::uint64_t snapshot_bytes = 0;  // every snapshot frame received
    std::uint64_t view_bodies = 0;     // bodies in those snapshots
    std::uint64_t delta_snapshots = 0;
    std::uint64_t delta_errors = 0;
    std::uint64_t shapes_received = 0;        // body shapes the snapshots described
    std::uint64_t shape_bytes = 0;            // their bytes (BodyShape and ShapeVertex)
    std::uint64_t bodies_without_shape = 0;   // bodies seen before their shape (a server bug)
    double bytes_per_body = 0;                // snapshot_bytes / view_bodies
    double delta_payload_bytes_per_body = 0;  // the codec's bytes alone, per body, over the deltas
    tally delta_problems;
    std::vector<std::pair<std::string, summary>> figures;  // in table order
    tally rejects;
    tally disconnects;
    tally failures;           // reason of each failed well-behaved bot
    tally misbehaving_drops;  // reason each misbehaving bot's session ended
    // The game: the scoreboard the well-behaved bots saw at the end (the first one's: the
    // Bye's when the match's end reached it), how many saw one and how many saw exactly it,
    // and each bot's (JSON only).
    std::vector<seen_line> scoreboard;
    bool scoreboard_final = false;
    std::uint32_t winner = 0;
    protocol::game_manifest game;                             // the game's own fields, teams...
    std::map<std::uint8_t, std::vector<std::int32_t>> teams;  // declared team values, by team
    std::uint8_t winning_team = 0;
    std::vector<std::uint32_t> winners;
    std::uint16_t tick_rate = 0;
    std::uint32_t scoreboards_seen = 0;
    std::uint32_t scoreboards_agreeing = 0;
    std::vector<bot_outcome> scoreboards;
    std::uint64_t game_bytes = 0;
    std::uint64_t game_events = 0;
    // 0: every well-behaved bot joined, kept its session and met no protocol error; else 1.
    int exit_code = 0;
};

// Summarises (and so sorts) the metrics' sample sets.
final_report make_report(fleet_metrics& metrics, std::span<const bot_outcome> outcomes, double seconds);

// "t=3s bots=100/100 snapshots/s=2000 rtt_ms_p50=0.31 ..." for the second just ended;
// summarises the interval sample sets (the caller clears them afterwards).
std::string progress_line(double t, std::uint32_t playing, std::uint32_t bots, double interval_s,
                          fleet_metrics& metrics);

std::string summary_table(const final_report& report);
nlohmann::json to_json(const final_report& report);

}  // namespace arena::bots
