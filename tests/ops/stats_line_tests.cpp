// The periodic stats log line, rendered from the match's and the process's report(): the same
// text, field for field, as the line the server has always written (scripts read it).
#include <catch2/catch.hpp>

#include "server/match/match.hpp"
#include "server/ops/process_counters.hpp"
#include "server/ops/stats_line.hpp"

using namespace arena::ops;

TEST_CASE("the stats log line lists the reported figures in their historic format", "[ops][stats]") {
    arena::match::match_counters c;
    c.ticks = 300;
    c.players = 2;
    c.players_in_grace = 1;  // still a player of the match on this line
    c.joins = 9;             // in --stats-json and /metrics, not on the line
    c.spectators = 1;        // beside the players, not among them
    c.rejects = {{arena::protocol::RejectCode::bad_input, 3}};
    process_counters p;
    p.tick_overruns = 4;
    p.connections_open = 5;
    p.bytes_in = 777;
    p.window = {0.0104, 0.02, 0.0316, 2880.4, 52000.6};
    stats_line_sink line;
    report(c, line);
    report(p, line);
    CHECK(line.line() ==
          "stats players=3 spectators=1 ticks=300 tick_ms_p50=0.010 tick_ms_p99=0.020 tick_ms_max=0.032 overruns=4 "
          "bytes_in_per_s=2880 bytes_out_per_s=52001 connections=5");
}
