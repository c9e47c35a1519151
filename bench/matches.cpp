// arena-bench-matches: what a match costs a process that hosts many (docs/MATCHES.md). Memory
// per empty match and per match of 8 players, and the tick work of N such matches on one
// thread: how many 8-player matches at 60 Hz one core can tick before ticks run late.
//
// The matches are real (the registry's, through the intake, as a transport drives them); the
// connections are stand-ins that keep each frame as a transport's output buffer does, so the
// figures hold the match's work and memory and none of the sockets'. bench/e2e.sh measures the
// same load end to end, transports included.
//
// Prints one JSON line.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "protocol/messages.hpp"
#include "protocol/version.hpp"
#include "server/host/intake.hpp"
#include "server/host/match_registry.hpp"
#include "server/world/presets.hpp"

using namespace arena;

namespace {

// Keeps the newest snapshot and the control frames, as a transport's bounded output does.
struct kept_connection : match::connection {
    std::string from;
    protocol::frame_bytes snapshot;
    std::vector<protocol::frame_bytes> control;
    explicit kept_connection(std::string address) : from(std::move(address)) {}
    void send(protocol::frame_bytes frame) override {
        control.push_back(std::move(frame));
        if (control.size() > 64) control.erase(control.begin());
    }
    void send_snapshot(const protocol::snapshot_encoder& s, uint32_t ack) override {
        send_snapshot_frame(s.frame_with_ack(ack));
    }
    void send_snapshot_frame(std::span<const uint8_t> frame) override { snapshot.assign(frame.begin(), frame.end()); }
    void close(protocol::RejectCode, std::string_view) override {}
    void close_with_bye(std::string_view) override {}
    std::string_view peer() const override { return from; }
};

double resident_mib() {
    std::ifstream statm("/proc/self/statm");
    long pages = 0, resident = 0;
    statm >> pages >> resident;
    return static_cast<double>(resident) * static_cast<double>(::sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

int64_t now_ns() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

host::registry_options room_options(uint32_t max_matches) {
    host::registry_options o;
    o.base.tick_rate = 60;
    o.base.snapshot_rate = 20;
    o.base.view_radius = 0;  // every body of a match in view, as bench/e2e.sh's run
    o.base.admission.max_players = 8;
    world::world_config room = world::asteroids_preset();
    room.rocks.count = 0;
    o.modes = {config::mode{"room8", room, "asteroids", 8, 0}};
    o.default_mode = "room8";
    o.max_matches = max_matches;
    o.max_matches_per_address = max_matches;
    return o;
}

struct players {
    std::vector<std::unique_ptr<kept_connection>> clients;
    uint32_t sequence = 0;
};

// Sends every client an Input (turning, thrusting), then ticks every match once.
int64_t tick_with_inputs(host::match_registry& matches, host::intake& in, players& p) {
    ++p.sequence;
    for (size_t i = 0; i < p.clients.size(); ++i) {
        protocol::input_msg input;
        input.sequence = p.sequence;
        input.thrust = (p.sequence / 60 + i) % 2 ? 1.0f : 0.3f;
        input.turn = (p.sequence / 45 + i) % 3 == 0 ? 1.0f : -0.5f;
        in.take(*p.clients[i], protocol::encode_input(input), std::nullopt);
    }
    const int64_t begin = now_ns();
    matches.tick_all(now_ns);
    return now_ns() - begin;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"arena-bench-matches: memory and tick work per match of 8 players", "arena-bench-matches"};
    uint32_t count = 200;
    uint32_t ticks = 600;
    app.add_option("--matches", count, "matches of each kind (empty, full)")->check(CLI::Range(1u, 10000u));
    app.add_option("--ticks", ticks, "ticks timed")->check(CLI::Range(60u, 100000u));
    CLI11_PARSE(app, argc, argv);

    // Empty matches: the registry's default plus `count` more, created as the lobby does.
    const double before_empty = resident_mib();
    host::match_registry empty_matches(room_options(count + 1));
    for (uint32_t i = 0; i < count; ++i) (void)empty_matches.create("room8", true);
    const double empty_mib = (resident_mib() - before_empty) / (count + 1);

    // Full matches: 8 players each, joined by Hello.mode (join-or-create fills them in turn).
    const double before_full = resident_mib();
    host::match_registry full_matches(room_options(count + 1));
    ops::process_counters counters;
    host::intake in(full_matches, counters);
    players p;
    for (uint32_t i = 0; i < 8 * count; ++i) {
        p.clients.push_back(std::make_unique<kept_connection>("10.0.0." + std::to_string(i % 250) + ":1"));
        kept_connection& c = *p.clients.back();
        full_matches.match_of(c).connect(c);
        const protocol::hello_msg hello{
            protocol::protocol_version, "p" + std::to_string(i), "", true, false, "", "room8"};
        in.take(c, protocol::encode_hello(hello), std::nullopt);
    }
    for (int i = 0; i < 120; ++i) tick_with_inputs(full_matches, in, p);  // warm: baselines, buffers
    const double full_mib = (resident_mib() - before_full) / (full_matches.size());

    std::vector<int64_t> spent;
    for (uint32_t i = 0; i < ticks; ++i) spent.push_back(tick_with_inputs(full_matches, in, p));
    std::sort(spent.begin(), spent.end());
    const double matches = static_cast<double>(full_matches.size());  // the default match filled first
    auto ms_at = [&](double q) {
        return static_cast<double>(spent[static_cast<size_t>(q * (spent.size() - 1))]) / 1e6;
    };
    double mean = 0;
    for (int64_t s : spent) mean += static_cast<double>(s) / 1e6;
    mean /= static_cast<double>(spent.size());
    const double budget_ms = 1000.0 / 60;
    std::printf(
        "{\"matches\": %.0f, \"players_per_match\": 8, \"empty_match_mib\": %.3f, \"full_match_mib\": %.3f, "
        "\"tick_ms\": {\"mean\": %.3f, \"p50\": %.3f, \"p99\": %.3f, \"max\": %.3f}, \"per_match_ms_mean\": %.4f, "
        "\"per_match_ms_p99\": %.4f, \"matches_per_core_at_p99\": %.0f}\n",
        matches, empty_mib, full_mib, mean, ms_at(0.5), ms_at(0.99), ms_at(1.0), mean / matches, ms_at(0.99) / matches,
        budget_ms / (ms_at(0.99) / matches));
    return 0;
}
