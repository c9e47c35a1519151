#include "bench/bandwidth.hpp"

#include <algorithm>
#include <cstdio>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "bench/timing.hpp"
#include "games/asteroids/asteroids_rules.hpp"
#include "protocol/decode.hpp"
#include "protocol/delta/receiver.hpp"
#include "protocol/game.hpp"
#include "protocol/verify.hpp"
#include "server/match/match.hpp"
#include "server/world/presets.hpp"
#include "server/world/rng.hpp"

namespace arena::bench {

namespace {

// A client at the end of a 100 ms round trip: it decodes what it receives (so every delta is
// proven decodable) and acknowledges a snapshot 6 ticks after it arrived.
struct measuring_client : match::connection {
    static constexpr uint32_t ack_delay_ticks = 6;
    explicit measuring_client(bool delta) : delta(delta) {}

    void send(protocol::frame_bytes) override {}
    // Kept, and read after the tick: the server's time is measured without the clients'.
    void send_snapshot(const protocol::snapshot_encoder& s, uint32_t ack) override { s.copy_with_ack(ack, pending); }
    void send_snapshot_frame(std::span<const uint8_t> frame) override { pending.assign(frame.begin(), frame.end()); }
    void close(protocol::RejectCode, std::string_view) override {}
    void close_with_bye(std::string_view) override {}
    std::string_view peer() const override { return "bench"; }

    void receive_pending() {
        if (pending.empty()) return;
        receive(pending);
        pending.clear();
    }

    void receive(std::span<const uint8_t> frame) {
        const auto m = protocol::verify_message(frame, protocol::server_frame_limits);
        if (!m) return ++errors, void();
        const auto s = protocol::decode_snapshot(*m.value);
        if (!s) return ++errors, void();
        if (!counting) return;
        ++snapshots;
        bytes += frame.size();
        if (!s.value.is_delta) {
            bodies += s.value.bodies.size();
            return;
        }
        if (s.value.table != nullptr) {
            protocol::game_list game;
            if (protocol::read_game(*s.value.table, game).empty()) {
                game_bytes += game.wire_bytes();
                events += game.events.size();
            }
        }
        payload += s.value.delta.size();
        const auto view = receiver->receive(s.value);
        if (!view) {
            if (errors++ == 0) std::fprintf(stderr, "bench bandwidth: %s\n", view.error.c_str());
            return;
        }
        bodies += view.value.size();
        arrived.push_back({now, receiver->ack()});
    }

    // The ack this client sends at tick `t`: the newest one that has had its round trip.
    uint32_t ack_at(uint32_t t) {
        while (!arrived.empty() && arrived.front().first + ack_delay_ticks <= t) {
            acked = arrived.front().second;
            arrived.pop_front();
        }
        return acked;
    }

    bool delta;
    std::optional<protocol::delta::receiver> receiver;
    std::vector<uint8_t> pending;
    bool counting = false;
    uint32_t now = 0;
    uint32_t acked = 0;
    std::deque<std::pair<uint32_t, uint32_t>> arrived;  // (tick received, ack it allows)
    uint64_t snapshots = 0, bytes = 0, payload = 0, bodies = 0, errors = 0, game_bytes = 0, events = 0;
};

// Hands one client message to the match as a transport does: verified, then received.
bool deliver(match::match& g, match::connection& c, const protocol::frame_bytes& frame) {
    auto verified = protocol::verify_message(frame, protocol::client_frame_limits);
    return verified && g.receive(c, *verified.value);
}

}  // namespace

namespace {

void run(uint32_t players, float view_radius, bool delta, uint32_t ticks, bool game) {
    match::match_config config;
    config.tick_rate = 60;
    config.snapshot_rate = 20;
    config.admission.max_players = players;
    config.view_radius = view_radius;
    config.seed = 7;
    world::world_config world_config = world::asteroids_preset();
    if (game) world_config.rules = "asteroids";
    match::match g(config, world_config);
    std::vector<std::unique_ptr<measuring_client>> clients;
    for (uint32_t i = 0; i < players; ++i) {
        clients.push_back(std::make_unique<measuring_client>(delta));
        clients.back()->receiver.emplace(config.tick_rate);
        g.connect(*clients.back());
        (void)deliver(g, *clients.back(), protocol::encode_hello(protocol::protocol_version, "p", "", delta));
    }
    // Every player moving: thrust and turn re-chosen every half second, thrust mostly forward.
    world::rng r(11);
    std::vector<protocol::input_msg> inputs(players);
    const uint32_t warmup = 120;
    std::vector<double> tick_ms;  // whole ticks: the step and this tick's share of snapshots
    for (uint32_t t = 0; t < warmup + ticks; ++t) {
        for (uint32_t i = 0; i < players; ++i) {
            measuring_client& c = *clients[i];
            c.now = t;
            c.counting = t >= warmup;
            protocol::input_msg& in = inputs[i];
            if (t % 30 == i % 30) {
                in.thrust = r.uniform(0.2f, 1.0f);
                in.turn = r.uniform(-1.0f, 1.0f);
            }
            in.sequence = t + 1;
            in.buttons = game ? rules::button_fire : 0;  // as often as the cooldown allows
            in.snapshot_ack = delta ? c.ack_at(t) : 0;
            (void)deliver(g, c, protocol::encode_input(in));
        }
        const auto t0 = clock::now();
        g.tick();
        if (t >= warmup) tick_ms.push_back(ms_between(t0, clock::now()));
        for (auto& c : clients) c->receive_pending();
    }
    uint64_t snapshots = 0, bytes = 0, payload = 0, bodies = 0, errors = 0, game_bytes = 0, events = 0;
    for (const auto& c : clients) {
        game_bytes += c->game_bytes;
        events += c->events;
        snapshots += c->snapshots;
        bytes += c->bytes;
        payload += c->payload;
        bodies += c->bodies;
        errors += c->errors;
    }
    const stats s = summarize(tick_ms);
    std::sort(tick_ms.begin(), tick_ms.end());
    const double p99 = tick_ms.empty() ? 0 : tick_ms[tick_ms.size() * 99 / 100];
    const auto per = [](uint64_t a, uint64_t b) {
        return b == 0 ? 0.0 : static_cast<double>(a) / static_cast<double>(b);
    };
    if (game) {
        const match::match_counters counters = g.counters();
        std::printf(
            "{\"bench\":\"game_bandwidth\",\"players\":%u,\"bodies\":%zu,\"view_radius\":%.0f,\"mode\":\"%s\","
            "\"ticks\":%u,\"snapshots\":%llu,\"errors\":%llu,\"shots\":%llu,\"hits\":%llu,\"kills\":%llu,"
            "\"bytes_per_snapshot\":%.1f,\"bodies_per_snapshot\":%.1f,\"payload_bytes_per_body\":%.3f,"
            "\"game_bytes_per_snapshot\":%.1f,\"events_per_snapshot\":%.2f,\"bytes_per_client_per_s\":%.0f,"
            "\"tick_ms_median\":%.3f,\"tick_ms_p99\":%.3f}\n",
            players, g.state().bodies().size(), view_radius, delta ? "delta" : "full", ticks,
            static_cast<unsigned long long>(snapshots), static_cast<unsigned long long>(errors),
            static_cast<unsigned long long>(counters.shots), static_cast<unsigned long long>(counters.hits),
            static_cast<unsigned long long>(counters.kills), per(bytes, snapshots), per(bodies, snapshots),
            per(payload, bodies), per(game_bytes, snapshots), per(events, snapshots),
            per(bytes, snapshots) * config.snapshot_rate, s.median, p99);
        std::fflush(stdout);
        return;
    }
    std::printf(
        "{\"bench\":\"bandwidth\",\"players\":%u,\"bodies\":%zu,\"view_radius\":%.0f,\"mode\":\"%s\","
        "\"ticks\":%u,\"snapshots\":%llu,\"errors\":%llu,\"bytes_per_snapshot\":%.1f,"
        "\"bodies_per_snapshot\":%.1f,\"bytes_per_body\":%.3f,\"payload_bytes_per_body\":%.3f,"
        "\"bytes_per_client_per_s\":%.0f,\"tick_ms_median\":%.3f,\"tick_ms_p99\":%.3f}\n",
        players, g.state().bodies().size(), view_radius, delta ? "delta" : "full", ticks,
        static_cast<unsigned long long>(snapshots), static_cast<unsigned long long>(errors), per(bytes, snapshots),
        per(bodies, snapshots), per(bytes, bodies), per(payload, bodies), per(bytes, snapshots) * config.snapshot_rate,
        s.median, p99);
    std::fflush(stdout);
}

}  // namespace

void bench_bandwidth(uint32_t players, float view_radius, bool delta, uint32_t ticks) {
    run(players, view_radius, delta, ticks, false);
}

void bench_game_bandwidth(uint32_t players, float view_radius, uint32_t ticks) {
    run(players, view_radius, true, ticks, true);
}

}  // namespace arena::bench
