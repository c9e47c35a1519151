#include "client_sim/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "protocol/delta/quantize.hpp"

namespace arena::bots {

namespace {

std::string format(const char* fmt, auto... args) {
    char buffer[256];
    std::snprintf(buffer, sizeof buffer, fmt, args...);
    return buffer;
}

double accuracy(const protocol::player_row& r) {
    return r.shots == 0 ? 0.0 : 100.0 * static_cast<double>(r.hits) / static_cast<double>(r.shots);
}

const char* state_name(protocol::PlayerState s) {
    const char* name = protocol::EnumNamePlayerState(s);
    return name != nullptr && *name != '\0' ? name : "?";
}

// Team k's name in `game` (1 is the first team), or its number.
std::string team_name(const protocol::game_manifest& game, std::int32_t team) {
    if (team >= 1 && static_cast<std::size_t>(team) <= game.teams.size()) return game.teams[team - 1].name;
    return team == 0 ? "-" : std::to_string(team);
}

// A declared value as a scoreboard shows it: a team by its name, a duration in seconds, anything
// else as a number.
std::string shown(const final_report& r, const protocol::game_field& field, std::int32_t value) {
    if (field.kind == protocol::GameFieldKind::team) return team_name(r.game, value);
    if (field.kind == protocol::GameFieldKind::ticks && r.tick_rate > 0)
        return format("%.1f s", static_cast<double>(value) / r.tick_rate);
    return std::to_string(value);
}

// Whether the protocol's own line (score, kills, deaths, shots, hits, lives) already shows every
// field the game declares: its table then stays the one scripts have always read.
bool line_shows_fields(const protocol::game_manifest& game) {
    for (const protocol::game_field& f : game.player_fields) {
        const std::string& n = f.name;
        if (n != "score" && n != "kills" && n != "deaths" && n != "shots" && n != "hits" && n != "lives") return false;
    }
    return true;
}

// The scoreboard by the game's own fields (its manifest), when it declares any.
void append_declared_scoreboard(std::string& out, const final_report& r) {
    out += format("  %-20s", "name");
    for (const protocol::game_field& f : r.game.player_fields) out += format(" %8s", f.label.c_str());
    out += "\n";
    for (const seen_line& l : r.scoreboard) {
        out += format("  %-20s", l.name.c_str());
        for (std::size_t k = 0; k < r.game.player_fields.size(); ++k)
            out += format(" %8s", shown(r, r.game.player_fields[k], k < l.values.size() ? l.values[k] : 0).c_str());
        out += "\n";
    }
    if (r.teams.empty()) return;
    out += "teams:";
    for (const auto& [team, values] : r.teams) {
        out += ' ';
        out += team_name(r.game, team);
        for (std::size_t k = 0; k < r.game.team_fields.size() && k < values.size(); ++k)
            out += format(" %s %d", r.game.team_fields[k].label.c_str(), values[k]);
        out += ";";
    }
    out += r.scoreboard_final
               ? format(" winner: %s\n", r.winning_team ? team_name(r.game, r.winning_team).c_str() : "nobody (a draw)")
               : "\n";
}

nlohmann::json lines_json(const std::vector<seen_line>& lines, const protocol::game_manifest& game = {}) {
    nlohmann::json out = nlohmann::json::array();
    for (const seen_line& l : lines) {
        out.push_back({{"player", l.row.player},
                       {"name", l.name},
                       {"score", l.row.score},
                       {"kills", l.row.kills},
                       {"deaths", l.row.deaths},
                       {"shots", l.row.shots},
                       {"hits", l.row.hits},
                       {"lives", l.row.lives},
                       {"state", state_name(l.row.state)}});
        // The game's own fields by their names, beside the protocol's (a name they share
        // is left as the protocol's).
        for (std::size_t k = 0; k < game.player_fields.size() && k < l.values.size(); ++k)
            if (!out.back().contains(game.player_fields[k].name)) out.back()[game.player_fields[k].name] = l.values[k];
    }
    return out;
}

void append_scoreboard(std::string& out, const final_report& r) {
    if (r.scoreboards_seen == 0) return;
    // The winners by name: the Bye's list (a tie, a team), else its one winner.
    std::string winners;
    for (const seen_line& l : r.scoreboard) {
        const bool won = r.winners.empty()
                             ? l.row.player == r.winner
                             : std::find(r.winners.begin(), r.winners.end(), l.row.player) != r.winners.end();
        if (!won) continue;
        if (!winners.empty()) winners += ", ";
        winners += l.name;
    }
    out += format("scoreboard (%s; winner: %s): %u of %u clients saw exactly this one\n",
                  r.scoreboard_final ? "final, from the server's Bye" : "the last lines, no Bye with the result",
                  winners.empty() ? "nobody" : winners.c_str(), r.scoreboards_agreeing, r.scoreboards_seen);
    if (!line_shows_fields(r.game)) {
        append_declared_scoreboard(out, r);
    } else {
        out += format("  %-20s %8s %6s %6s %6s %6s %9s\n", "name", "score", "kills", "deaths", "shots", "hits",
                      "accuracy");
        for (const seen_line& l : r.scoreboard) {
            out += format("  %-20s %8u %6u %6u %6u %6u %7.1f %%\n", l.name.c_str(), l.row.score, l.row.kills,
                          l.row.deaths, l.row.shots, l.row.hits, accuracy(l.row));
        }
    }
    out += format("game: %llu events heard, %llu bytes of lines, names and events\n",
                  static_cast<unsigned long long>(r.game_events), static_cast<unsigned long long>(r.game_bytes));
}

nlohmann::json tally_json(const tally& t) {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& [reason, count] : t) j[reason] = count;
    return j;
}

void append_tally(std::string& out, const char* title, const tally& t) {
    if (t.empty()) return;
    out += title;
    out += ":\n";
    for (const auto& [reason, count] : t)
        out += format("  %6llu  %s\n", static_cast<unsigned long long>(count), reason.c_str());
}

}  // namespace

final_report make_report(fleet_metrics& m, std::span<const bot_outcome> outcomes, double seconds) {
    final_report r;
    r.seconds = seconds;
    r.bots = static_cast<std::uint32_t>(outcomes.size());
    for (const bot_outcome& o : outcomes) {
        if (o.joined) ++r.joined;
        if (o.misbehaving) {
            ++r.misbehaving;
            if (o.ended_early) {
                ++r.misbehaving_dropped;
                ++r.misbehaving_drops[o.reason];
            }
        } else if (o.ended_early) {
            ++r.ended_early;
        }
        if (o.failed()) {
            ++r.failed;
            ++r.failures[o.reason.empty() ? "did not join before the run ended" : o.reason];
        }
    }
    for (const bot_outcome& o : outcomes) {
        if (o.misbehaving || o.scoreboard.empty()) continue;
        if (r.scoreboards_seen++ == 0) {
            r.scoreboard = o.scoreboard;
            r.scoreboard_final = o.final_scoreboard;
            r.winner = o.winner;
            r.game = o.game;
            r.teams = o.teams;
            r.winning_team = o.winning_team;
            r.winners = o.winners;
            r.tick_rate = o.tick_rate;
        }
        if (o.scoreboard == r.scoreboard && o.final_scoreboard == r.scoreboard_final) ++r.scoreboards_agreeing;
        r.scoreboards.push_back(o);
    }
    r.game_bytes = m.game_bytes;
    r.game_events = m.game_events;
    r.bytes_in = m.bytes_in;
    r.bytes_out = m.bytes_out;
    r.snapshots = m.snapshots;
    r.inputs_sent = m.inputs_sent;
    r.inputs_left_out = m.inputs_left_out;
    r.ticks_skipped = m.ticks_skipped;
    r.snapshot_bytes = m.snapshot_bytes;
    r.view_bodies = m.view_bodies;
    r.delta_snapshots = m.delta_snapshots;
    r.delta_errors = m.delta_errors;
    r.shapes_received = m.shapes_received;
    r.shape_bytes = m.shape_bytes;
    r.bodies_without_shape = m.bodies_without_shape;
    r.delta_problems = m.delta_problems;
    if (m.delta_bodies != 0)
        r.delta_payload_bytes_per_body =
            static_cast<double>(m.delta_payload_bytes) / static_cast<double>(m.delta_bodies);
    if (m.view_bodies != 0)
        r.bytes_per_body = static_cast<double>(m.snapshot_bytes) / static_cast<double>(m.view_bodies);
    if (!m.prediction_error_m.empty())
        r.prediction_exact_share =
            static_cast<double>(m.predictions_exact) / static_cast<double>(m.prediction_error_m.size());
    r.own_shots = m.own_shots;
    r.hits = m.hits;
    if (const std::uint64_t matched = m.own_shots.exact + m.own_shots.with_error; matched != 0)
        r.own_shot_exact_share = static_cast<double>(m.own_shots.exact) / static_cast<double>(matched);
    r.figures = {
        {"rtt_ms", m.rtt_ms.summarize()},
        {"network_rtt_ms", m.network_rtt_ms.summarize()},
        {"server_hold_ms", m.server_hold_ms.summarize()},
        {"snapshot_gap_ms", m.snapshot_gap_ms.summarize()},
        {"snapshots_per_s_per_bot", m.snapshots_per_s_per_bot.summarize()},
        {"prediction_error_m", m.prediction_error_m.summarize()},
        {"input_lag_ticks", m.input_lag_ticks.summarize()},
        {"bodies_in_view", m.bodies_in_view.summarize()},
        {"snapshot_bytes", m.snapshot_bytes_each.summarize()},
        {"snapshots_per_s", m.snapshots_per_s.summarize()},
        {"bytes_in_per_s", m.bytes_in_per_s.summarize()},
        {"bytes_out_per_s", m.bytes_out_per_s.summarize()},
        {"own_shot_error_m", m.own_shot_error_m.summarize()},
        {"hit_after_seen_ms", m.hit_after_seen_ms.summarize()},
    };
    r.rejects = m.rejects;
    r.disconnects = m.disconnects;
    // Bots played (joined, behaving) yet no snapshot ever confirmed a prediction: the run
    // measured nothing and must not pass. (Masses of 1e-45 once put NaN in every snapshot,
    // and the bots exited 0 with an empty prediction figure.)
    std::uint32_t played = 0;
    for (const bot_outcome& o : outcomes) played += o.joined && !o.misbehaving ? 1 : 0;
    const bool no_samples = played > 0 && m.prediction_error_m.empty();
    if (no_samples) ++r.failures[no_prediction_samples];
    r.exit_code = r.failed == 0 && !no_samples ? 0 : 1;
    return r;
}

std::string progress_line(double t, std::uint32_t playing, std::uint32_t bots, double interval_s, fleet_metrics& m) {
    const double per_s = interval_s > 0 ? 1.0 / interval_s : 0.0;
    const summary rtt = m.interval_rtt_ms.summarize();
    const summary err = m.interval_prediction_error_m.summarize();
    return format(
        "t=%.0fs bots=%u/%u snapshots/s=%.0f rtt_ms_p50=%.2f rtt_ms_p99=%.2f pred_err_m_p99=%.4f "
        "bytes_in/s=%.0f bytes_out/s=%.0f",
        t, playing, bots, static_cast<double>(m.interval_snapshots) * per_s, rtt.p50, rtt.p99, err.p99,
        static_cast<double>(m.interval_bytes_in) * per_s, static_cast<double>(m.interval_bytes_out) * per_s);
}

std::string summary_table(const final_report& r) {
    std::string out = format(
        "arena-bots: %u bots, %u joined, %u failed, %u ended early, %u misbehaving (%u dropped), "
        "%.1f s\n",
        r.bots, r.joined, r.failed, r.ended_early, r.misbehaving, r.misbehaving_dropped, r.seconds);
    out += format("%-26s %9s %12s %12s %12s %12s %12s\n", "figure", "count", "mean", "min", "p50", "p99", "max");
    for (const auto& [name, s] : r.figures) {
        out += format("%-26s %9zu %12.4f %12.4f %12.4f %12.4f %12.4f\n", name.c_str(), s.count, s.mean, s.min, s.p50,
                      s.p99, s.max);
    }
    out += format("predictions exactly right: %.2f %%\n", 100.0 * r.prediction_exact_share);
    const shot_counts& shots = r.own_shots;
    const summary* shot_error = nullptr;
    for (const auto& [name, s] : r.figures)
        if (name == "own_shot_error_m") shot_error = &s;
    // A ship reaches the client rounded: its position to 1/256 m (off by up to 1/512 m on each
    // axis), its velocity to 1/32 m/s (1/64 m/s), which the prediction carries from the
    // snapshot to the shot: about 0.1 s (a snapshot interval of 3 ticks and the client's lead
    // of a few). So a predicted shot is off by up to √2·(1/512 + 0.1/64) m ≈ 5.0 mm, and
    // bit-exact only by chance: within that, its error is the quantisation, not a fault.
    constexpr double prediction_s = 0.1;
    const double quantum_m =
        std::sqrt(2.0) * (0.5 / protocol::delta::position_scale + prediction_s * 0.5 / protocol::delta::velocity_scale);
    const double p99_m = shot_error != nullptr ? shot_error->p99 : 0.0;
    out += format(
        "own shots: %llu matched the server's, error p99 %.1f mm: %s the delta snapshots' quantisation (%.1f mm; "
        "%.2f %% bit-exact), %llu unconfirmed, %llu unpredicted\n",
        static_cast<unsigned long long>(shots.exact + shots.with_error), p99_m * 1e3,
        p99_m <= quantum_m ? "within" : "beyond", quantum_m * 1e3, 100.0 * r.own_shot_exact_share,
        static_cast<unsigned long long>(shots.unconfirmed), static_cast<unsigned long long>(shots.unpredicted));
    const hit_counts& hits = r.hits;
    const std::uint64_t server_hits = hits.confirmed + hits.unclaimed_hits;
    out += format(
        "hit registration: %llu claimed, %.1f %% confirmed, %llu unclaimed server hits (%.1f %%), "
        "%llu unconfirmed claims on targets something else took first\n",
        static_cast<unsigned long long>(hits.claimed),
        hits.claimed != 0 ? 100.0 * static_cast<double>(hits.confirmed) / static_cast<double>(hits.claimed) : 0.0,
        static_cast<unsigned long long>(hits.unclaimed_hits),
        server_hits != 0 ? 100.0 * static_cast<double>(hits.unclaimed_hits) / static_cast<double>(server_hits) : 0.0,
        static_cast<unsigned long long>(hits.contested));
    out += format(
        "totals: bytes_in=%llu bytes_out=%llu snapshots=%llu inputs=%llu ticks_skipped=%llu inputs_left_out=%llu\n",
        static_cast<unsigned long long>(r.bytes_in), static_cast<unsigned long long>(r.bytes_out),
        static_cast<unsigned long long>(r.snapshots), static_cast<unsigned long long>(r.inputs_sent),
        static_cast<unsigned long long>(r.ticks_skipped), static_cast<unsigned long long>(r.inputs_left_out));
    out += format(
        "snapshots: %llu deltas (%llu did not decode), %.2f bytes per body in view (frames), "
        "%.2f (delta payload)\n",
        static_cast<unsigned long long>(r.delta_snapshots), static_cast<unsigned long long>(r.delta_errors),
        r.bytes_per_body, r.delta_payload_bytes_per_body);
    out += format("shapes: %llu received (%llu bytes), %llu bodies seen without one\n",
                  static_cast<unsigned long long>(r.shapes_received), static_cast<unsigned long long>(r.shape_bytes),
                  static_cast<unsigned long long>(r.bodies_without_shape));
    append_scoreboard(out, r);
    append_tally(out, "rejects", r.rejects);
    append_tally(out, "delta problems", r.delta_problems);
    append_tally(out, "disconnects", r.disconnects);
    append_tally(out, "misbehaving bots dropped", r.misbehaving_drops);
    append_tally(out, "failures", r.failures);
    out += format("exit code %d\n", r.exit_code);
    return out;
}

nlohmann::json to_json(const final_report& r) {
    nlohmann::json figures = nlohmann::json::object();
    for (const auto& [name, s] : r.figures) {
        figures[name] = {{"count", s.count}, {"mean", s.mean}, {"min", s.min},
                         {"p50", s.p50},     {"p99", s.p99},   {"max", s.max}};
    }
    nlohmann::json boards = nlohmann::json::array();
    for (const bot_outcome& o : r.scoreboards) {
        boards.push_back({{"bot", o.name},
                          {"final", o.final_scoreboard},
                          {"winner", o.winner},
                          {"lines", lines_json(o.scoreboard, o.game)}});
    }
    return {
        {"seconds", r.seconds},
        {"scoreboard",
         {{"final", r.scoreboard_final},
          {"winner", r.winner},
          {"clients", r.scoreboards_seen},
          {"agreeing", r.scoreboards_agreeing},
          {"lines", lines_json(r.scoreboard, r.game)},
          {"game_events", r.game_events},
          {"game_bytes", r.game_bytes}}},
        {"scoreboards", boards},
        {"bots", r.bots},
        {"joined", r.joined},
        {"failed", r.failed},
        {"ended_early", r.ended_early},
        {"misbehaving", r.misbehaving},
        {"misbehaving_dropped", r.misbehaving_dropped},
        {"totals",
         {{"bytes_in", r.bytes_in},
          {"bytes_out", r.bytes_out},
          {"snapshots", r.snapshots},
          {"inputs", r.inputs_sent},
          {"ticks_skipped", r.ticks_skipped},
          {"inputs_left_out", r.inputs_left_out},
          {"snapshot_bytes", r.snapshot_bytes},
          {"view_bodies", r.view_bodies},
          {"delta_snapshots", r.delta_snapshots},
          {"delta_errors", r.delta_errors},
          {"shapes_received", r.shapes_received},
          {"shape_bytes", r.shape_bytes},
          {"bodies_without_shape", r.bodies_without_shape}}},
        {"bytes_per_body", r.bytes_per_body},
        {"delta_payload_bytes_per_body", r.delta_payload_bytes_per_body},
        {"delta_problems", tally_json(r.delta_problems)},
        {"figures", figures},
        {"prediction_exact_share", r.prediction_exact_share},
        {"own_shots",
         {{"exact", r.own_shots.exact},
          {"with_error", r.own_shots.with_error},
          {"unconfirmed", r.own_shots.unconfirmed},
          {"unpredicted", r.own_shots.unpredicted},
          {"exact_share", r.own_shot_exact_share}}},
        {"hit_registration",
         {{"claimed", r.hits.claimed},
          {"confirmed", r.hits.confirmed},
          {"unclaimed_hits", r.hits.unclaimed_hits},
          {"contested", r.hits.contested}}},
        {"rejects", tally_json(r.rejects)},
        {"disconnects", tally_json(r.disconnects)},
        {"misbehaving_drops", tally_json(r.misbehaving_drops)},
        {"failures", tally_json(r.failures)},
        {"exit_code", r.exit_code},
    };
}

}  // namespace arena::bots
