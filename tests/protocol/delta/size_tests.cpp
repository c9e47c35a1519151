// Sizes: bytes per body in view for the delta codec's reference scenes, at 60 Hz ticks and
// 20 Hz snapshots (3 ticks between a snapshot and its baseline), against BodyState's 32 bytes.
// Prints a table; checks the bandwidth target of at most 4 bytes per body for a mixed scene
// of 1/3 thrusting, turning players and 2/3 drifting rocks.
#include <catch2/catch.hpp>

#include <cstdio>
#include <deque>
#include <optional>
#include <vector>

#include "protocol/delta/codec.hpp"
#include "scenes.hpp"

namespace ad = arena::protocol::delta;
using ad::test::motion;

namespace {

constexpr std::uint32_t tick_rate = 60;
constexpr std::uint32_t ticks_per_snapshot = 3;

struct scene_spec {
    const char* name;
    std::uint32_t players, rocks, resting;
    std::uint32_t baseline_age = 1;  // in snapshots: 1 = the previous one
    bool full = false;
};

// Average encoded bytes per body in view over `snapshots` snapshots after a warm-up.
double bytes_per_body(const scene_spec& s, int snapshots = 200) {
    ad::test::rng r(31);
    auto bodies = ad::test::make_bodies(r, motion::player, s.players, 400, 1);
    for (motion kind : {motion::drift, motion::rest}) {
        const std::uint32_t n = kind == motion::drift ? s.rocks : s.resting;
        auto more = ad::test::make_bodies(r, kind, n, 400, static_cast<std::uint32_t>(bodies.size()) + 1);
        bodies.insert(bodies.end(), more.begin(), more.end());
    }
    std::deque<std::vector<ad::quantized_body>> sent;
    std::vector<std::uint8_t> bytes;
    std::uint64_t total_bytes = 0, total_bodies = 0;
    for (int snap = -20; snap < snapshots; ++snap) {
        for (std::uint32_t t = 0; t < ticks_per_snapshot; ++t) ad::test::step(bodies, r, 1.0f / tick_rate);
        const auto view = ad::test::quantize_view(bodies);
        std::optional<ad::view> baseline;
        if (!s.full && sent.size() >= s.baseline_age) baseline = ad::view(sent[sent.size() - s.baseline_age]);
        const ad::elapsed_time e{ticks_per_snapshot * s.baseline_age, tick_rate};
        ad::encode(view, baseline, e, bytes);
        REQUIRE(ad::decode(bytes, baseline, e).value == view);  // the sizes are of correct deltas
        if (snap >= 0) {
            total_bytes += bytes.size();
            total_bodies += view.size();
        }
        sent.push_back(view);
        if (sent.size() > 8) sent.pop_front();
    }
    return static_cast<double>(total_bytes) / static_cast<double>(total_bodies);
}

}  // namespace

TEST_CASE("Bytes per body in view, delta against full, printed", "[protocol][delta][size]") {
    const scene_spec specs[] = {
        {"(a) drifting rocks (constant v, ω)", 0, 300, 0},   {"(b) thrusting, turning players", 300, 0, 0},
        {"(c) unchanged bodies (at rest)", 0, 0, 300},       {"(d) full snapshot, mixed scene", 100, 200, 0, 1, true},
        {"mixed 1/3 players, 2/3 rocks", 100, 200, 0},       {"mixed, 30 bodies in view", 10, 20, 0},
        {"mixed, baseline 3 snapshots old", 100, 200, 0, 3}, {"mixed, baseline 8 snapshots old", 100, 200, 0, 8},
    };
    std::printf("\n%-38s %10s %12s\n", "scene (60 Hz ticks, 20 Hz snapshots)", "B/body", "vs 32 B");
    double mixed = 0;
    for (const scene_spec& s : specs) {
        const double b = bytes_per_body(s);
        std::printf("%-38s %10.3f %11.1fx\n", s.name, b, 32.0 / b);
        if (s.players == 100 && s.rocks == 200 && !s.full && s.baseline_age == 1) mixed = b;
    }
    std::printf("(BodyState alone is 32 B per body; the FlatBuffers snapshot adds its header.)\n\n");
    CHECK(mixed <= 4.0);
}
