// --stats-json: the run's figures at exit, for the benchmarks, capacity planning and scripts.
#include <sys/resource.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "protocol/version.hpp"
#include "server/config/scoreboard_json.hpp"
#include "server/host/host.hpp"
#include "server/host/log.hpp"
#include "server/host/stats_json.hpp"

namespace arena::host {

namespace {

double ms(int64_t ns) {
    return static_cast<double>(ns) / 1e6;
}

// CPU time and peak memory of this process.
nlohmann::json process_figures() {
    rusage usage{};
    ::getrusage(RUSAGE_SELF, &usage);
    auto seconds = [](const timeval& t) {
        return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_usec) / 1e6;
    };
    return {{"cpu_user_s", seconds(usage.ru_utime)},
            {"cpu_system_s", seconds(usage.ru_stime)},
            {"peak_rss_kib", usage.ru_maxrss}};
}

}  // namespace

void process_host::write_stats_json(const std::string& path) const {
    const double seconds = static_cast<double>(now_ns() - started_ns_) / 1e9;
    const ops::process_counters p = process_counters();
    nlohmann::json j = {
        {"duration_s", seconds},
        {"tick_rate", options_.match.tick_rate},
        {"snapshot_rate", options_.match.snapshot_rate},
        {"tick_ms",
         {{"p50", ms(run_ticks_.quantile_ns(0.5))},
          {"p99", ms(run_ticks_.quantile_ns(0.99))},
          {"max", ms(run_ticks_.max_ns())},
          {"mean", run_ticks_.mean_ns() / 1e6}}},
        {"snapshots", {{"view_radius", options_.match.view_radius}}},
        {"limits",
         {{"max_players", options_.match.admission.max_players},
          {"max_spectators", options_.match.admission.max_spectators},
          {"max_connections", matches_.default_match().rules().connection_limit()},
          {"max_pending_handshakes", matches_.default_match().rules().pending_limit()},
          {"max_inputs_per_second", matches_.default_match().rules().input_limit()},
          {"input_buffer", options_.match.input_buffer},
          {"max_frame_bytes", protocol::max_client_frame_body},
          {"max_control_frames", options_.max_control_frames},
          {"socket_send_buffer", options_.socket_send_buffer},
          {"handshake_timeout_s", std::chrono::duration<double>(options_.match.admission.handshake_timeout).count()},
          {"idle_timeout_s", std::chrono::duration<double>(options_.match.admission.idle_timeout).count()},
          {"stall_timeout_s", static_cast<double>(options_.stall_timeout_ns) / 1e9}}},
        {"process", process_figures()},
        {"bytes_in_per_s", seconds > 0 ? static_cast<double>(p.bytes_in) / seconds : 0},
        {"bytes_out_per_s", seconds > 0 ? static_cast<double>(p.bytes_out) / seconds : 0},
    };
    // Every counter, as the match and the process name them (the same list /metrics reads).
    // The game's scoreboard (an empty array under sandbox rules), as arena-replay --scoreboard prints it.
    std::vector<rules::score_line> lines;
    std::vector<std::string> names;
    for (const match::match::named_score& s : matches_.default_match().scoreboard()) {
        lines.push_back(s.line);
        names.push_back(s.name);
    }
    const protocol::game_manifest game = matches_.default_match().game_rules().manifest();
    j["scoreboard"] = nlohmann::json::parse(config::scoreboard_json(lines, names, &game));
    // The player the rules declare the winner, as every client's last Bye says (0: nobody).
    j["winner"] = matches_.default_match().game_rules().winner();
    // A team game's teams and scores, and the team winning (0: a draw).
    if (const std::vector<rules::team_line> teams = matches_.default_match().game_rules().teams(); !teams.empty()) {
        nlohmann::json list = nlohmann::json::array();
        for (const rules::team_line& t : teams)
            list.push_back({{"team", t.team}, {"name", t.name}, {"score", t.score}});
        j["teams"] = std::move(list);
        j["winning_team"] = matches_.default_match().game_rules().winning_team();
    }
    stats_json_sink figures(j);
    report(matches_.default_match().counters(), figures);
    report(p, figures);
    // Every match that ran (the running ones first, the default one first), with its own figures
    // and scoreboard.
    nlohmann::json matches = nlohmann::json::array();
    for (const match_summary& s : matches_.summaries()) {
        std::vector<rules::score_line> board;
        std::vector<std::string> board_names;
        for (const match::match::named_score& n : s.scoreboard) {
            board.push_back(n.line);
            board_names.push_back(n.name);
        }
        nlohmann::json one = {{"id", s.id},
                              {"mode", s.mode},
                              {"ended", s.ended},
                              {"winner", s.winner},
                              {"ticks_late", s.ticks_late},
                              {"ticks_dropped", s.ticks_dropped}};
        one["scoreboard"] = nlohmann::json::parse(config::scoreboard_json(board, board_names));
        stats_json_sink match_figures(one);
        report(s.counters, match_figures);
        matches.push_back(std::move(one));
    }
    j["matches"] = std::move(matches);
    j["matches_created"] = matches_.created();
    std::ofstream out(path);
    out << j.dump(2) << "\n";
    if (!out) log_line("cannot write stats to %s", path.c_str());
}

}  // namespace arena::host
