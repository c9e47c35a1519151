// The codec's round trip: a client applying each delta holds exactly the server's quantised
// view, tick after tick, over a long random session with joins, leaves, owner changes, jumps,
// extreme values and baselines that are missing, fresh or several snapshots stale.
#include <catch2/catch.hpp>

#include <algorithm>
#include <deque>
#include <limits>
#include <optional>
#include <vector>

#include "protocol/delta/codec.hpp"
#include "scenes.hpp"

namespace ad = arena::protocol::delta;
using ad::test::evolve;
using ad::test::random_body;
using ad::test::rng;

constexpr std::int32_t i32min = std::numeric_limits<std::int32_t>::min();
constexpr std::int32_t i32max = std::numeric_limits<std::int32_t>::max();

namespace {

void require_round_trip(ad::view current, std::optional<ad::view> baseline, ad::elapsed_time e) {
    const std::vector<std::uint8_t> bytes = ad::encode(current, baseline, e);
    const auto decoded = ad::decode(bytes, baseline, e);
    INFO("decode: " << decoded.error);
    REQUIRE(decoded.ok());
    REQUIRE(decoded.value.size() == current.size());
    REQUIRE(std::equal(current.begin(), current.end(), decoded.value.begin()));
}

}  // namespace

TEST_CASE("A long random session round-trips exactly every snapshot, whatever the baseline",
          "[protocol][delta][property]") {
    for (std::uint32_t rate : {60u, 20u, 7u}) {
        rng r(rate);
        std::vector<ad::quantized_body> view;
        for (std::uint32_t id = 0; id < 3000; ++id) {
            if (r.chance(0.8)) view.push_back(random_body(r, id * 3));
        }
        struct sent {
            std::uint32_t tick;
            std::vector<ad::quantized_body> bodies;
        };
        std::deque<sent> ring;  // the server's last views; the client holds the same ones
        std::uint32_t tick = 0;
        std::size_t fulls = 0, fresh = 0, stale = 0;
        for (int snapshot = 0; snapshot < 200; ++snapshot) {
            const auto ticks = static_cast<std::uint32_t>(1 + r.below(4));
            tick += ticks;
            evolve(view, r, ticks, rate);
            INFO("rate " << rate << " snapshot " << snapshot << " bodies " << view.size());
            std::optional<ad::view> baseline;
            std::uint32_t base_tick = tick;
            const double roll = r.uniform();
            if (ring.empty() || roll < 0.1) {
                ++fulls;
            } else {
                const std::size_t back = roll < 0.6 ? 0 : r.below(ring.size());
                const sent& s = ring[ring.size() - 1 - back];
                baseline = ad::view(s.bodies);
                base_tick = s.tick;
                ++(back == 0 ? fresh : stale);
            }
            require_round_trip(view, baseline, {tick - base_tick, rate});
            ring.push_back({tick, view});
            if (ring.size() > 8) ring.pop_front();
        }
        CHECK(fulls > 5);
        CHECK(fresh > 50);
        CHECK(stale > 30);
    }
}

TEST_CASE("Edge views round-trip: empty, all removed, all added, id 0 and the largest id", "[protocol][delta]") {
    rng r(11);
    const std::vector<ad::quantized_body> none;
    std::vector<ad::quantized_body> some;
    for (std::uint32_t id : {0u, 1u, 2u, 1000u, 0xfffffffeu, 0xffffffffu}) some.push_back(random_body(r, id));
    const ad::elapsed_time e{3, 60};
    require_round_trip(none, std::nullopt, e);
    require_round_trip(none, ad::view(none), e);
    require_round_trip(some, std::nullopt, e);
    require_round_trip(some, ad::view(none), e);
    require_round_trip(none, ad::view(some), e);
    require_round_trip(some, ad::view(some), e);
}

TEST_CASE("Extreme values and elapsed times round-trip: prediction never overflows", "[protocol][delta]") {
    std::vector<ad::quantized_body> base, cur;
    std::uint32_t id = 1;
    for (std::int32_t x : {i32min, i32max, 0}) {
        for (std::int32_t v : {i32min, i32max, 0, -1}) {
            for (std::int16_t w : {std::int16_t{-32768}, std::int16_t{32767}, std::int16_t{0}}) {
                base.push_back({id, 0, x, x, v, v, std::int16_t{32767}, w});
                cur.push_back({id, 7, ~x, x, ~v, v, std::int16_t{-32768}, static_cast<std::int16_t>(-w - 1)});
                ++id;
            }
        }
    }
    for (std::uint32_t ticks : {0u, 1u, 3u, 65535u, 65536u, 0xffffffffu}) {
        for (std::uint32_t rate : {1u, 60u, 0xffffffffu}) {
            require_round_trip(cur, ad::view(base), {ticks, rate});
            require_round_trip(base, ad::view(base), {ticks, rate});
            require_round_trip(base, ad::view(cur), {ticks, rate});
        }
    }
}

TEST_CASE("Bodies exactly as predicted cost about one bit: the codec uses the prediction", "[protocol][delta]") {
    rng r(12);
    auto bodies = ad::test::make_bodies(r, ad::test::motion::drift, 1000, 400);
    for (auto& b : bodies) b.vx = b.vy = b.w = 0;  // at rest: prediction is exact
    const auto view = ad::test::quantize_view(bodies);
    const auto bytes = ad::encode(view, ad::view(view), {3, 60});
    CHECK(bytes.size() < 16);  // a header and a handful of bits for 1000 bodies
    // A drifting body whose position moved by exactly v·t is also free: its residual is 0.
    // Velocities in 1/32 m/s, positions in 1/256 m, angular velocity in 1/256 rad/s.
    std::vector<ad::quantized_body> base{{1, 0, 0, 0, 32 * 60, -32 * 30, 0, 256}};
    std::vector<ad::quantized_body> cur = base;
    cur[0].x = 256 * 3;       // 60 m/s for 3 ticks at 60 Hz: 3 m
    cur[0].y = -256 * 3 / 2;  // −30 m/s: −1.5 m
    cur[0].angle = static_cast<std::int16_t>(32768 * 0.05 / 3.14159265358979 + 0.5);  // 1 rad/s for 0.05 s
    const auto moving = ad::encode(cur, ad::view(base), {3, 60});
    const auto still = ad::encode(base, ad::view(base), {0, 60});
    CHECK(moving.size() == still.size());
    require_round_trip(cur, ad::view(base), {3, 60});
}
