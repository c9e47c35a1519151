// The /metrics body: Prometheus text format, naming conventions, and promtool's verdict.
#include <catch2/catch.hpp>

#include "common/run_command.hpp"

#include <unistd.h>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "server/match/match.hpp"
#include "server/ops/metrics.hpp"
#include "server/ops/process_counters.hpp"
#include "server/ops/process_stats.hpp"
#include "server/ops/text_format.hpp"

using namespace arena::ops;

namespace {

server_metrics sample_metrics() {
    server_metrics m;
    for (double s : {0.0001, 0.0004, 0.0009, 0.003, 0.02, 0.5}) m.tick_duration_s.observe(s);
    m.tick_budget_s = 1.0 / 60;
    // The figures as the server reports them: through the match's and the process's report().
    arena::match::match_counters c;
    c.ticks = 600;
    c.players = 3;
    c.players_in_grace = 2;
    c.max_players = 64;
    c.joins = 5;
    c.leaves = 2;
    c.rejects = {{arena::protocol::RejectCode::bad_input, 1}};
    c.closes = {{"bad_input", 1}, {"odd\"reason\\x", 7}};  // a label value that needs escaping
    c.snapshots_sent = 120;
    c.snapshot_bytes = 812;
    c.inputs_received = 290;
    c.input_underruns = 4;
    c.input_overflows = 1;
    process_counters p;
    p.tick_overruns = 2;
    p.connections_open = 4;
    p.bytes_in = 1234;
    p.bytes_out = 98765;
    p.messages_in = 300;
    p.messages_out = 400;
    m.figures = [c, p](arena::match::figure_sink& out) {
        report(c, out);
        report(p, out);
    };
    mode_figures& asteroids = m.modes["asteroids"];
    asteroids.matches = 3;
    asteroids.players = 17;
    asteroids.tick_duration_s.observe(0.0004);
    asteroids.ticks_late = 12;
    asteroids.ticks_dropped = 1;
    m.modes["sandbox"].matches = 1;
    m.version = "1.2.3";
    m.process = read_process_stats();
    return m;
}

// A sample line parsed back: name, labels as text, value.
struct parsed_sample {
    std::string name, labels, value;
};

// Minimal reading of the text format: every non-comment line is NAME[{LABELS}] VALUE, every
// family has HELP then TYPE before its samples.
struct parsed_text {
    std::map<std::string, std::string> types;  // family -> type
    std::vector<parsed_sample> samples;
};

parsed_text parse(const std::string& text) {
    parsed_text out;
    std::istringstream lines(text);
    std::string line, last_help;
    while (std::getline(lines, line)) {
        REQUIRE_FALSE(line.empty());
        if (line.rfind("# HELP ", 0) == 0) {
            last_help = line.substr(7, line.find(' ', 7) - 7);
            continue;
        }
        if (line.rfind("# TYPE ", 0) == 0) {
            std::istringstream parts(line.substr(7));
            std::string name, type;
            parts >> name >> type;
            CHECK(name == last_help);  // HELP comes right before TYPE, for the same family
            CHECK(out.types.count(name) == 0);
            out.types[name] = type;
            continue;
        }
        parsed_sample s;
        const size_t brace = line.find('{');
        const size_t space = line.rfind(' ');
        REQUIRE(space != std::string::npos);
        if (brace != std::string::npos && brace < space) {
            s.name = line.substr(0, brace);
            s.labels = line.substr(brace + 1, line.rfind('}') - brace - 1);
        } else {
            s.name = line.substr(0, space);
        }
        s.value = line.substr(space + 1);
        out.samples.push_back(s);
    }
    return out;
}

std::string family_of(const std::string& sample_name, const std::map<std::string, std::string>& types) {
    if (types.count(sample_name)) return sample_name;
    for (const char* suffix : {"_bucket", "_sum", "_count"}) {
        const std::string s = suffix;
        if (sample_name.size() > s.size() && sample_name.compare(sample_name.size() - s.size(), s.size(), s) == 0) {
            const std::string base = sample_name.substr(0, sample_name.size() - s.size());
            if (types.count(base)) return base;
        }
    }
    return "";
}

std::string value_of(const parsed_text& p, const std::string& name, const std::string& labels = "") {
    for (const auto& s : p.samples)
        if (s.name == name && s.labels == labels) return s.value;
    return "(missing)";
}

}  // namespace

TEST_CASE("ops metrics: numbers are spelled the way Prometheus parses them", "[ops][metrics]") {
    CHECK(format_number(0.0005) == "0.0005");
    CHECK(format_number(0.0166) == "0.0166");
    CHECK(format_number(1) == "1");
    CHECK(format_number(1.0 / 0.0) == "+Inf");
    CHECK(format_number(-1.0 / 0.0) == "-Inf");
    CHECK(format_number(0.0 / 0.0) == "NaN");
    CHECK(escape_label_value("a\"b\\c\nd") == "a\\\"b\\\\c\\nd");
    CHECK(escape_help("x\\y\nz") == "x\\\\y\\nz");
}

TEST_CASE("ops metrics: a histogram renders cumulative buckets, +Inf, _sum and _count", "[ops][metrics]") {
    histogram h({0.001, 0.01});
    h.observe(0.001);  // on the bound: "less than or equal" puts it in the first bucket
    h.observe(0.005);
    h.observe(0.5);
    text_writer w;
    w.histogram_family("x_seconds", "help", h);
    CHECK(w.text() ==
          "# HELP x_seconds help\n# TYPE x_seconds histogram\n"
          "x_seconds_bucket{le=\"0.001\"} 1\nx_seconds_bucket{le=\"0.01\"} 2\nx_seconds_bucket{le=\"+Inf\"} 3\n"
          "x_seconds_sum 0.506\nx_seconds_count 3\n");
}

TEST_CASE(
    "ops metrics: every metric has HELP and TYPE, counters end in _total, names carry the arena_ or process_ prefix",
    "[ops][metrics]") {
    const parsed_text p = parse(render_metrics(sample_metrics()));
    REQUIRE(p.types.size() > 20);
    for (const auto& [name, type] : p.types) {
        INFO(name);
        CHECK((name.rfind("arena_", 0) == 0 || name.rfind("process_", 0) == 0));
        if (type == "counter") CHECK(name.size() > 6);
        if (type == "counter") CHECK(name.compare(name.size() - 6, 6, "_total") == 0);
        CHECK((type == "counter" || type == "gauge" || type == "histogram"));
    }
    for (const auto& s : p.samples) {
        INFO(s.name);
        CHECK_FALSE(family_of(s.name, p.types).empty());
        CHECK(s.labels.find("player") == std::string::npos);
    }
}

TEST_CASE("ops metrics: the rendered values are the server's figures", "[ops][metrics]") {
    const parsed_text p = parse(render_metrics(sample_metrics()));
    CHECK(p.types.at("arena_tick_duration_seconds") == "histogram");
    CHECK(value_of(p, "arena_tick_duration_seconds_bucket", "le=\"0.0005\"") == "2");
    CHECK(value_of(p, "arena_tick_duration_seconds_bucket", "le=\"0.001\"") == "3");
    CHECK(value_of(p, "arena_tick_duration_seconds_bucket", "le=\"0.0166\"") == "4");
    CHECK(value_of(p, "arena_tick_duration_seconds_bucket", "le=\"0.033\"") == "5");
    CHECK(value_of(p, "arena_tick_duration_seconds_bucket", "le=\"+Inf\"") == "6");
    CHECK(value_of(p, "arena_tick_duration_seconds_count") == "6");
    CHECK(value_of(p, "arena_tick_overruns_total") == "2");
    CHECK(value_of(p, "arena_players_connected") == "3");
    CHECK(value_of(p, "arena_players_in_grace") == "2");
    CHECK(value_of(p, "arena_player_joins_total") == "5");
    CHECK(value_of(p, "arena_player_leaves_total") == "2");
    CHECK(value_of(p, "arena_rejects_total", "reason=\"bad_input\"") == "1");
    CHECK(value_of(p, "arena_rejects_total", "reason=\"server_full\"") == "0");
    CHECK(value_of(p, "arena_closes_total", "reason=\"odd\\\"reason\\\\x\"") == "7");
    CHECK(value_of(p, "arena_received_bytes_total") == "1234");
    CHECK(value_of(p, "arena_sent_bytes_total") == "98765");
    CHECK(value_of(p, "arena_received_messages_total") == "300");
    CHECK(value_of(p, "arena_sent_messages_total") == "400");
    CHECK(value_of(p, "arena_snapshot_size_bytes") == "812");
    CHECK(value_of(p, "arena_input_underruns_total") == "4");
    CHECK(value_of(p, "arena_input_overflows_total") == "1");
    CHECK(value_of(p, "arena_build_info", "version=\"1.2.3\"") == "1");
    CHECK(value_of(p, "arena_draining") == "0");
    CHECK(value_of(p, "arena_matches", "mode=\"asteroids\"") == "3");
    CHECK(value_of(p, "arena_matches", "mode=\"sandbox\"") == "1");
    CHECK(value_of(p, "arena_players", "mode=\"asteroids\"") == "17");
    CHECK(value_of(p, "arena_match_tick_duration_seconds_count", "mode=\"asteroids\"") == "1");
    CHECK(p.types.at("arena_match_ticks_late_total") == "counter");
    CHECK(value_of(p, "arena_match_ticks_late_total", "mode=\"asteroids\"") == "12");
    CHECK(value_of(p, "arena_match_ticks_late_total", "mode=\"sandbox\"") == "0");
    CHECK(value_of(p, "arena_match_ticks_dropped_total", "mode=\"asteroids\"") == "1");
}

TEST_CASE("ops metrics: process figures come from /proc/self", "[ops][metrics]") {
    const process_stats s = read_process_stats();
    REQUIRE(s.available);
    CHECK(s.resident_memory_bytes > 1e5);
    CHECK(s.cpu_seconds >= 0);
    CHECK(s.open_fds >= 3);
    // Started within the last hour, by the wall clock.
    const double now = static_cast<double>(std::time(nullptr));
    CHECK(s.start_time_seconds > now - 3600);
    CHECK(s.start_time_seconds <= now + 1);
    const parsed_text p = parse(render_metrics(sample_metrics()));
    for (const char* name : {"process_resident_memory_bytes", "process_cpu_seconds_total", "process_start_time_seconds",
                             "process_open_fds", "process_max_fds", "process_virtual_memory_bytes"})
        CHECK(p.types.count(name) == 1);
}

TEST_CASE("ops metrics: /proc/self/stat is read from the last parenthesis, whatever the command name",
          "[ops][metrics]") {
    proc_stat_fields f;
    const std::string stat = "42 (a) b (c) R 1 42 42 0 -1 4194560 100 0 0 0 7 3 0 0 20 0 1 0 12345 1000 10 rest";
    REQUIRE(parse_proc_self_stat(stat, f));
    CHECK(f.utime_ticks == 7);
    CHECK(f.stime_ticks == 3);
    CHECK(f.start_ticks == 12345);
    CHECK_FALSE(parse_proc_self_stat("42 (short) R 1 2", f));
    CHECK(parse_boot_time("cpu 1 2 3\nbtime 1700000000\nprocesses 9\n") == 1700000000u);
    CHECK(parse_boot_time("cpu 1 2 3\n") == 0);
}

TEST_CASE("ops metrics: promtool check metrics accepts the output", "[ops][metrics][promtool]") {
    if (std::system("command -v promtool >/dev/null 2>&1") != 0) {
        WARN("promtool not found (Debian package 'prometheus'; `make deps` installs it): skipped");
        return;
    }
    char path[] = "/tmp/arena-metrics-XXXXXX";
    const int fd = mkstemp(path);
    REQUIRE(fd >= 0);
    close(fd);
    {
        std::ofstream out(path);
        out << render_metrics(sample_metrics());
    }
    const auto checked = arena::test::run_command(std::string("promtool check metrics < ") + path + " 2>&1");
    std::remove(path);
    INFO(checked.output);
    CHECK(checked.exit_code == 0);
    CHECK(checked.output.empty());
}
