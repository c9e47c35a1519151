// arena-bench: the world and protocol benchmarks, one JSON line per measurement on
// stdout (bench/table.py turns them into the table of bench/README.md).
//
//   step       world step, asteroids preset with collisions, 1k / 10k / 100k bodies
//   integrate  forces + semi-implicit Euler over 1M bodies, next to a streaming copy of as many bytes
//   snapshot   snapshot_encoder::build + copy_with_ack: bodies per second, bytes per body
//   replay     a recorded 64-player session re-simulated through the replayer, × real time
//   bandwidth  256 moving players, full against delta snapshots, whole world and a view radius;
//              1000 players with a view radius
//   game       Asteroids rules, 32 players all firing: bytes per client with the game's lines and events
//
// usage: arena-bench [--only step,integrate,snapshot,replay,bandwidth,game] [--quick]
#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "bench/bandwidth.hpp"
#include "bench/cases.hpp"

int main(int argc, char** argv) {
    std::string only = "step,integrate,snapshot,replay,bandwidth,game";
    bool quick = false;
    std::string tmp_dir = "/tmp";
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--only") && i + 1 < argc) {
            only = argv[++i];
        } else if (!std::strcmp(argv[i], "--quick")) {
            quick = true;
        } else if (!std::strcmp(argv[i], "--tmp") && i + 1 < argc) {
            tmp_dir = argv[++i];
        } else {
            std::fprintf(
                stderr,
                "usage: arena-bench [--only step,integrate,snapshot,replay,bandwidth,game] [--quick] [--tmp DIR]\n");
            return 2;
        }
    }
    std::vector<std::string> cases;
    for (size_t at = 0; at <= only.size();) {
        const size_t comma = std::min(only.find(',', at), only.size());
        cases.push_back(only.substr(at, comma - at));
        at = comma + 1;
    }
    auto wants = [&](const char* name) {
        return std::find(cases.begin(), cases.end(), name) != cases.end();
    };
    using namespace arena::bench;
    if (wants("step")) {
        bench_world_step(1000, 60, quick ? 120 : 600);
        bench_world_step(10000, 60, quick ? 60 : 300);
        bench_world_step(100000, quick ? 10 : 30, quick ? 10 : 60);
    }
    if (wants("integrate")) bench_integration(1000000, quick ? 10 : 40);
    if (wants("snapshot")) {
        bench_snapshot(1000, 64, quick ? 200 : 1000);
        bench_snapshot(10000, 64, quick ? 50 : 200);
    }
    if (wants("replay")) {
        if (!bench_replay(64, quick ? 600 : 3600, tmp_dir + "/arena-bench-64p.arpl")) return 1;
    }
    if (wants("bandwidth")) {
        const uint32_t ticks = quick ? 300 : 1200;
        for (float radius : {0.0f, 100.0f}) {
            bench_bandwidth(256, radius, false, ticks);
            bench_bandwidth(256, radius, true, ticks);
        }
        bench_bandwidth(1000, 50.0f, true, quick ? 150 : 600);
    }
    // Asteroids as a game, 32 players all firing: the game's bytes on top of the views.
    if (wants("game")) bench_game_bandwidth(32, 100.0f, quick ? 600 : 2400);
    return 0;
}
