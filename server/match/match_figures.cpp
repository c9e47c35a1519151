// The match's figures, named once for --stats-json, /metrics and the stats log line (figures.hpp).
#include "server/match/match.hpp"

namespace arena::match {

void report(const match_counters& c, figure_sink& out) {
    // The log line counts a player in the grace too: its body is still in the match.
    out.gauge({"", "", "", "players"}, c.players + c.players_in_grace);
    // Spectators have no body and no score line: counted apart from the players everywhere.
    out.gauge({"spectators", "arena_spectators_connected", "Spectators watching the match (no body, no score line).",
               "spectators"},
              c.spectators);
    out.counter({"ticks", "arena_ticks_total", "World steps run.", "ticks"}, c.ticks);
    // The game rules' scoreboard summed over the players (zero under sandbox rules).
    out.counter({"shots", "arena_shots_total", "Bullets fired by every player."}, c.shots);
    out.counter({"hits", "arena_hits_total", "Bullets that hit a rock or a ship."}, c.hits);
    out.counter({"kills", "arena_kills_total", "Ships destroyed by another player's bullet."}, c.kills);
    out.gauge({"", "arena_players_connected", "Players in the match with a live connection."}, c.players);
    out.gauge({"", "arena_players_in_grace", "Dropped players whose bodies wait for them to reconnect."},
              c.players_in_grace);
    out.gauge({"", "arena_players_max", "Players the match admits at once."}, c.max_players);
    out.gauge({"players_peak", "arena_players_peak", "Most players in the match at once."}, uint64_t{c.players_peak});
    out.counter({"joins", "arena_player_joins_total", "Players who joined the match."}, c.joins);
    out.counter({"leaves", "arena_player_leaves_total", "Players who left the match, for any reason."}, c.leaves);
    out.counter({"reconnects", "arena_reconnects_total", "Players who came back to their body within the grace."},
                c.reconnects);
    out.counter({"takeovers", "arena_takeovers_total", "Players taken over by a new connection with their identity."},
                c.takeovers);
    // Every code from 0, so that rate() sees the first reject of a kind.
    std::map<std::string, uint64_t> rejects;
    for (const char* const* n = protocol::EnumNamesRejectCode(); *n; ++n) rejects[*n] = 0;
    for (const auto& [code, count] : c.rejects) rejects[protocol::EnumNameRejectCode(code)] = count;
    out.counters_by({"rejects", "arena_rejects_total", "Connections refused or dropped with a Reject, by reason code."},
                    "reason", rejects);
    out.counters_by({"closes", "arena_closes_total", "Connections ended, by why."}, "reason", c.closes);
    out.counter({"inputs_received", "arena_inputs_received_total", "Input messages received from players."},
                c.inputs_received);
    out.counter({"input_underruns", "arena_input_underruns_total", "Ticks that found a player's input buffer empty."},
                c.input_underruns);
    out.counter({"input_overflows", "arena_input_overflows_total",
                 "Inputs that arrived to a full buffer and dropped the oldest."},
                c.input_overflows);
    out.counter({"stale_inputs", "arena_stale_inputs_total", "Inputs ignored: not newer than the last received."},
                c.stale_inputs);
    out.counter({"inputs_recovered", "arena_inputs_recovered_total",
                 "Inputs taken from a later Input's earlier list: their own message was lost or late."},
                c.inputs_recovered);
    out.counter({"inputs_lost", "arena_inputs_lost_total",
                 "Input sequences the world never got: skipped, and not repeated in a later Input's earlier list."},
                c.inputs_lost);
    out.counter({"snapshots_sent", "arena_snapshots_sent_total", "Snapshots sent, one per client per broadcast."},
                c.snapshots_sent);
    out.gauge({"", "arena_snapshot_size_bytes", "Size of the last snapshot frame built."}, c.snapshot_bytes);
    const fanout_counters& s = c.snapshots;
    out.counter({"snapshots/delta_frames", "", ""}, s.delta_frames);
    out.counter({"snapshots/keyframes", "", ""}, s.keyframes);
    out.counter({"snapshots/full_frames", "", ""}, s.full_frames);
    out.counter({"snapshots/delta_bytes", "", ""}, s.delta_bytes);
    out.counter({"snapshots/delta_payload_bytes", "", ""}, s.delta_payload_bytes);
    out.counter({"snapshots/delta_bodies", "", ""}, s.delta_bodies);
    out.counter({"snapshots/shapes_sent", "", ""}, s.shapes_sent);
    out.counter({"snapshots/shape_bytes", "", ""}, s.shape_bytes);
    out.counter({"snapshots/trimmed_frames", "arena_snapshots_trimmed_total",
                 "Delta snapshots that held only part of their view, to fit their client's byte budget."},
                s.trimmed_frames);
    out.counter({"snapshots/left_out_bodies", "", ""}, s.left_out_bodies);
    out.gauge({"snapshots/delta_bytes_per_body", "", ""},
              s.delta_bodies == 0 ? 0.0 : static_cast<double>(s.delta_bytes) / static_cast<double>(s.delta_bodies));
}

}  // namespace arena::match
