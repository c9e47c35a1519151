#include "bench/cases.hpp"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <vector>

#include "bench/timing.hpp"
#include "protocol/snapshot.hpp"
#include "scenes/scatter.hpp"
#include "scenes/sticks.hpp"
#include "server/match/body_state.hpp"
#include "server/match/tick_record.hpp"
#include "server/replay/header.hpp"
#include "server/replay/recorder.hpp"
#include "server/replay/replayer.hpp"
#include "server/world/integrate.hpp"
#include "server/world/presets.hpp"
#include "server/world/rng.hpp"
#include "server/world/world.hpp"

namespace arena::bench {

namespace {

// Keeps the optimiser from dropping work whose result nobody reads.
volatile uint64_t sink = 0;

// The world's step timer (server/world/profile.hpp) on this process's steady clock.
int64_t steady_now_ns(void*) {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(clock::now().time_since_epoch()).count();
}

}  // namespace

world::world_config scaled_asteroids(uint32_t bodies) {
    world::world_config config = world::asteroids_preset();
    if (bodies > config.rocks.count) {
        const float scale = std::sqrt(static_cast<float>(bodies) / static_cast<float>(config.rocks.count));
        config.size *= scale;
    }
    config.rocks.count = bodies;
    // The scene these figures have always measured: circle rocks, frictionless (world version 1
    // had no contact friction), so that a change of speed is the code's, not the scene's.
    config.rocks.polygon_vertices = 0;
    config.rocks.material.friction = 0;
    return config;
}

void bench_world_step(uint32_t bodies, int warmup, int steps) {
    const auto t0 = clock::now();
    world::world w(scaled_asteroids(bodies), 1);
    const double setup_ms = ms_between(t0, clock::now());
    const stats s = time_samples(warmup, steps, [&] { w.step({}); });
    const uint64_t hash = w.hash();
    const size_t contacts = w.last_contacts().size();
    // Then as many steps again with the per-phase timer on, apart from the timed ones so that
    // its clock reads cost them nothing: the mean ms per step of each phase.
    w.set_step_timer({steady_now_ns, nullptr});
    for (int k = 0; k < steps; ++k) w.step({});
    const world::step_profile& p = w.profile();
    std::string phases;
    for (size_t i = 0; i < world::step_phase_count; ++i) {
        char field[64];
        std::snprintf(field, sizeof field, "%s\"%s\":%.4f", i ? "," : "",
                      world::step_phase_name(static_cast<world::step_phase>(i)),
                      p.ms(static_cast<world::step_phase>(i)));
        phases += field;
    }
    std::printf(
        "{\"bench\":\"world_step\",\"preset\":\"asteroids\",\"n\":%zu,\"warmup\":%d,\"steps\":%d,"
        "\"ms_per_step_median\":%.4f,\"ms_per_step_p90\":%.4f,\"ms_per_step_min\":%.4f,"
        "\"ns_per_body\":%.2f,\"contacts_last_step\":%zu,\"world_side_m\":%.1f,\"setup_ms\":%.1f,"
        "\"hash\":\"%016" PRIx64 "\",\"profile_ms\":{%s}}\n",
        w.bodies().size(), warmup, steps, s.median, s.p90, s.min, s.median * 1e6 / static_cast<double>(bodies),
        contacts, static_cast<double>(w.config().size.x()), setup_ms, hash, phases.c_str());
    std::fflush(stdout);
}

void bench_integration(uint32_t bodies, int samples) {
    const world::world_config config = scaled_asteroids(bodies);
    std::vector<world::body> state;
    state.reserve(bodies);
    world::rng r(7);
    const scenes::scatter_box box{{0, 0}, config.size, config.rocks.min_radius, config.rocks.max_radius};
    for (uint32_t i = 0; i < bodies; ++i) {
        world::body b = scenes::scattered_circle(r, box, config.rocks.material);
        const float vx = r.uniform(-config.rocks.max_speed, config.rocks.max_speed);
        const float vy = r.uniform(-config.rocks.max_speed, config.rocks.max_speed);
        const float w = r.uniform(-3, 3);
        b.velocity = {vx, vy};
        b.angular_velocity = w;
        b.id = i + 1;
        state.push_back(b);
    }
    const size_t bytes = state.size() * sizeof(world::body);
    std::vector<unsigned char> src(bytes), dst(bytes);
    std::memcpy(src.data(), state.data(), bytes);
    // Interleaved, so both see the same machine weather.
    std::vector<double> integrate_ms, copy_ms;
    for (int k = 0; k < samples + 3; ++k) {
        auto t0 = clock::now();
        world::integrate_free_bodies(state, config);
        auto t1 = clock::now();
        std::memcpy(dst.data(), src.data(), bytes);
        auto t2 = clock::now();
        sink = sink + dst[static_cast<size_t>(k) % bytes];
        if (k < 3) continue;  // warm-up: page faults, caches
        integrate_ms.push_back(ms_between(t0, t1));
        copy_ms.push_back(ms_between(t1, t2));
    }
    const stats si = summarize(integrate_ms), sc = summarize(copy_ms);
    std::printf(
        "{\"bench\":\"integrate\",\"n\":%u,\"samples\":%d,\"bytes\":%zu,\"body_bytes\":%zu,"
        "\"integrate_ms_median\":%.3f,\"integrate_ms_p90\":%.3f,\"copy_ms_median\":%.3f,\"copy_ms_p90\":%.3f,"
        "\"ratio\":%.2f,\"integrate_gb_per_s\":%.2f,\"copy_gb_per_s\":%.2f,\"ns_per_body\":%.2f}\n",
        bodies, samples, bytes, sizeof(world::body), si.median, si.p90, sc.median, sc.p90, si.median / sc.median,
        static_cast<double>(bytes) / (si.median * 1e6), static_cast<double>(bytes) / (sc.median * 1e6),
        si.median * 1e6 / bodies);
    std::fflush(stdout);
}

void bench_snapshot(uint32_t bodies, uint32_t clients, int samples) {
    world::world w(scaled_asteroids(bodies), 3);
    for (int k = 0; k < 10; ++k) w.step({});
    std::vector<protocol::BodyState> states;
    protocol::snapshot_encoder encoder;
    // As snapshot_fanout::shared_frame does it: world bodies → BodyState, then one build.
    auto build = [&] {
        states.clear();
        for (const world::body& b : w.bodies()) states.push_back(match::body_state(b));
        encoder.build(w.tick(), states);
    };
    const stats sb = time_samples(10, samples, build);
    std::vector<std::vector<uint8_t>> out(clients);
    uint32_t ack = 0;
    const stats sc = time_samples(10, samples, [&] {
        for (auto& o : out) encoder.copy_with_ack(++ack, o);
    });
    const double frame = static_cast<double>(encoder.frame().size());
    std::printf(
        "{\"bench\":\"snapshot\",\"n\":%u,\"clients\":%u,\"samples\":%d,\"frame_bytes\":%.0f,"
        "\"bytes_per_body\":%.2f,\"build_ms_median\":%.4f,\"build_ms_p90\":%.4f,"
        "\"bodies_per_s\":%.4g,\"copy_all_clients_ms_median\":%.4f,\"copy_per_client_us\":%.3f,"
        "\"body_copies_per_s\":%.4g}\n",
        bodies, clients, samples, frame, frame / bodies, sb.median, sb.p90, bodies / (sb.median * 1e-3), sc.median,
        sc.median * 1e3 / clients, static_cast<double>(bodies) * clients / (sc.median * 1e-3));
    std::fflush(stdout);
}

bool bench_replay(uint32_t players, uint32_t ticks, const std::string& path) {
    const world::world_config config = world::asteroids_preset();
    const uint64_t seed = 20261121;
    const uint32_t tick_rate = 60;
    {
        world::world w(config, seed);
        auto opened = replay::recorder::open(path, replay::make_header(w, "asteroids", seed, tick_rate));
        if (!opened) {
            std::fprintf(stderr, "arena-bench: %s\n", opened.error.c_str());
            return false;
        }
        replay::recorder& rec = opened.value;
        world::rng script(11);
        std::vector<world::body_id> body_of;  // by player
        std::vector<world::player_input> stick(players);
        for (uint32_t k = 0; k < ticks; ++k) {
            match::tick_record record;
            record.tick = w.tick();
            if (k == 0)
                for (uint32_t p = 1; p <= players; ++p) record.joins.emplace_back(p);
            for (uint32_t p = 0; p < body_of.size(); ++p) {
                // A human's stick: held for a while, then moved.
                scenes::move_stick_now_and_then(script, stick[p]);
                world::player_input in = stick[p];
                in.buttons = script.next_u64() % 40 == 0 ? world::button_impulse : 0;
                record.inputs.push_back({body_of[p], in});
            }
            const auto spawned = match::apply_tick(w, record);
            body_of.insert(body_of.end(), spawned.begin(), spawned.end());
            if (auto s = rec.record_tick(record, w.hash()); !s) {
                std::fprintf(stderr, "arena-bench: %s\n", s.error.c_str());
                return false;
            }
        }
        if (auto s = rec.finish(w.tick(), w.hash()); !s) {
            std::fprintf(stderr, "arena-bench: %s\n", s.error.c_str());
            return false;
        }
    }
    std::vector<double> runs;
    replay::replay_report report;
    for (int rep = 0; rep < 3; ++rep) {
        const auto t0 = clock::now();
        auto opened = replay::replayer::open(path);
        if (!opened) {
            std::fprintf(stderr, "arena-bench: %s\n", opened.error.c_str());
            return false;
        }
        report = opened.value->run();
        runs.push_back(ms_between(t0, clock::now()));
        if (!report.complete || report.mismatch) {
            std::fprintf(stderr, "arena-bench: replay of %s failed: %s\n", path.c_str(), report.error.c_str());
            return false;
        }
    }
    std::remove(path.c_str());
    const stats s = summarize(runs);
    const double ticks_per_s = report.ticks_replayed / (s.median * 1e-3);
    std::printf(
        "{\"bench\":\"replay\",\"players\":%u,\"ticks\":%u,\"tick_rate\":%u,\"bodies\":%zu,"
        "\"hashes_checked\":%u,\"ms_median\":%.2f,\"ticks_per_s\":%.0f,\"x_real_time\":%.1f}\n",
        players, report.ticks_replayed, tick_rate, config.rocks.count + static_cast<size_t>(players),
        report.hashes_checked, s.median, ticks_per_s, ticks_per_s / tick_rate);
    std::fflush(stdout);
    return true;
}

}  // namespace arena::bench
