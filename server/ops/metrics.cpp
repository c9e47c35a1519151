#include "server/ops/metrics.hpp"

#include "server/ops/text_format.hpp"

#ifndef ARENA_VERSION
#define ARENA_VERSION "unknown"
#endif

namespace arena::ops {

namespace {

void counter(text_writer& w, const char* name, const char* help, uint64_t value) {
    w.family(name, "counter", help);
    w.sample(name, value);
}

void gauge(text_writer& w, const char* name, const char* help, double value) {
    w.family(name, "gauge", help);
    w.sample(name, value);
}

void render_tick(text_writer& w, const server_metrics& m) {
    w.histogram_family("arena_tick_duration_seconds", "Time spent in one world step.", m.tick_duration_s);
    counter(w, "arena_ticks_total", "World steps run.", m.ticks);
    counter(w, "arena_tick_overruns_total", "Ticks dropped because the tick loop fell behind.", m.tick_overruns);
    gauge(w, "arena_tick_budget_seconds", "Time one tick may take at the configured tick rate.", m.tick_budget_s);
}

void render_players(text_writer& w, const server_metrics& m) {
    gauge(w, "arena_players_connected", "Players in the match.", static_cast<double>(m.players_connected));
    gauge(w, "arena_players_max", "Players the match admits at once.", static_cast<double>(m.players_max));
    gauge(w, "arena_connections_open", "Open client connections, joined or not.",
          static_cast<double>(m.connections_open));
    counter(w, "arena_player_joins_total", "Players who joined the match.", m.joins);
    counter(w, "arena_player_leaves_total", "Players who left the match, for any reason.", m.leaves);
    w.family("arena_rejects_total", "counter", "Connections refused or dropped with a Reject, by reason code.");
    for (const auto& [reason, count] : m.rejects) w.sample("arena_rejects_total", count, {{"reason", reason}});
}

void render_traffic(text_writer& w, const server_metrics& m) {
    counter(w, "arena_received_bytes_total", "Bytes read from clients.", m.bytes_in);
    counter(w, "arena_sent_bytes_total", "Bytes written to clients.", m.bytes_out);
    counter(w, "arena_received_messages_total", "Protocol messages read from clients.", m.messages_in);
    counter(w, "arena_sent_messages_total", "Protocol messages written to clients.", m.messages_out);
    counter(w, "arena_snapshots_sent_total", "Snapshots sent, one per client per broadcast.", m.snapshots_sent);
    gauge(w, "arena_snapshot_size_bytes", "Size of the last snapshot frame built.",
          static_cast<double>(m.snapshot_size_bytes));
    counter(w, "arena_inputs_received_total", "Input messages received from players.", m.inputs_received);
    counter(w, "arena_input_underruns_total", "Ticks that found a player's input buffer empty.", m.input_underruns);
    counter(w, "arena_input_overflows_total", "Inputs that arrived to a full buffer and dropped the oldest.",
            m.input_overflows);
}

void render_lifecycle(text_writer& w, const server_metrics& m) {
    gauge(w, "arena_draining", "1 while the server shuts down and admits no new players.", m.draining ? 1 : 0);
    w.family("arena_build_info", "gauge", "Always 1; the labels say which build is running.");
    w.sample("arena_build_info", 1.0, {{"version", m.version.empty() ? build_version() : m.version}});
}

void render_process(text_writer& w, const process_stats& p) {
    if (!p.available) return;  // absent rather than a misleading zero
    w.family("process_cpu_seconds_total", "counter", "Total user and system CPU time spent in seconds.");
    w.sample("process_cpu_seconds_total", p.cpu_seconds);
    gauge(w, "process_resident_memory_bytes", "Resident memory size in bytes.", p.resident_memory_bytes);
    gauge(w, "process_virtual_memory_bytes", "Virtual memory size in bytes.", p.virtual_memory_bytes);
    gauge(w, "process_start_time_seconds", "Start time of the process since unix epoch in seconds.",
          p.start_time_seconds);
    gauge(w, "process_open_fds", "Number of open file descriptors.", p.open_fds);
    gauge(w, "process_max_fds", "Maximum number of open file descriptors.", p.max_fds);
}

}  // namespace

const char* build_version() {
    return ARENA_VERSION;
}

std::string render_metrics(const server_metrics& m) {
    text_writer w;
    render_tick(w, m);
    render_players(w, m);
    render_traffic(w, m);
    render_lifecycle(w, m);
    render_process(w, m.process);
    return w.text();
}

}  // namespace arena::ops
