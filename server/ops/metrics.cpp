#include "server/ops/metrics.hpp"

#include "server/ops/text_format.hpp"

#ifndef ARENA_VERSION
#define ARENA_VERSION "unknown"
#endif

namespace arena::ops {

namespace {

void gauge(text_writer& w, const char* name, const char* help, double value) {
    w.family(name, "gauge", help);
    w.sample(name, value);
}

// Each figure with a metric name becomes one family.
class metrics_sink : public match::figure_sink {
public:
    explicit metrics_sink(text_writer& w) : w_(w) {}
    void counter(const match::figure& f, uint64_t value) override {
        if (f.metric.empty()) return;
        w_.family(f.metric, "counter", f.help);
        w_.sample(f.metric, value);
    }
    void gauge(const match::figure& f, uint64_t value) override { gauge(f, static_cast<double>(value)); }
    void gauge(const match::figure& f, double value) override {
        if (f.metric.empty()) return;
        w_.family(f.metric, "gauge", f.help);
        w_.sample(f.metric, value);
    }
    void counters_by(const match::figure& f, std::string_view label,
                     const std::map<std::string, uint64_t>& values) override {
        if (f.metric.empty()) return;
        w_.family(f.metric, "counter", f.help);
        for (const auto& [key, count] : values) w_.sample(f.metric, count, {{std::string(label), key}});
    }

private:
    text_writer& w_;
};

void render_tick(text_writer& w, const server_metrics& m) {
    w.histogram_family("arena_tick_duration_seconds", "Time spent in one world step.", m.tick_duration_s);
    gauge(w, "arena_tick_budget_seconds", "Time one tick may take at the configured tick rate.", m.tick_budget_s);
}

void render_modes(text_writer& w, const server_metrics& m) {
    if (m.modes.empty()) return;
    w.family("arena_matches", "gauge", "Matches running now, by mode.");
    for (const auto& [mode, f] : m.modes) w.sample("arena_matches", f.matches, {{"mode", mode}});
    w.family("arena_players", "gauge", "Players with a live connection now, by mode.");
    for (const auto& [mode, f] : m.modes) w.sample("arena_players", f.players, {{"mode", mode}});
    w.family("arena_match_tick_duration_seconds", "histogram", "Time one match spends in one world step, by mode.");
    for (const auto& [mode, f] : m.modes)
        w.histogram_samples("arena_match_tick_duration_seconds", f.tick_duration_s, {{"mode", mode}});
    w.family("arena_match_ticks_late_total", "counter",
             "Match ticks run more than a tick interval after they fell due (the process fell behind), by mode.");
    for (const auto& [mode, f] : m.modes) w.sample("arena_match_ticks_late_total", f.ticks_late, {{"mode", mode}});
    w.family("arena_match_ticks_dropped_total", "counter",
             "Match ticks given up because the process fell further behind than it catches up, by mode.");
    for (const auto& [mode, f] : m.modes)
        w.sample("arena_match_ticks_dropped_total", f.ticks_dropped, {{"mode", mode}});
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
    render_modes(w, m);
    if (m.figures) {
        metrics_sink figures(w);
        m.figures(figures);
    }
    render_lifecycle(w, m);
    render_process(w, m.process);
    return w.text();
}

}  // namespace arena::ops
