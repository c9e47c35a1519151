// The shared encoder: many views of the same two states, each decoded by the ordinary
// decode() to exactly the view it encodes, whatever subset of the state and baseline it is.
#include <catch2/catch.hpp>

#include <algorithm>
#include <deque>
#include <optional>
#include <vector>

#include "protocol/delta/codec.hpp"
#include "protocol/delta/shared_encoder.hpp"
#include "scenes.hpp"

namespace ad = arena::protocol::delta;
using ad::test::rng;

namespace {

// A random subset of the state's indices: every body with probability `share`.
std::vector<std::uint32_t> random_view(rng& r, std::size_t size, double share) {
    std::vector<std::uint32_t> out;
    for (std::uint32_t i = 0; i < size; ++i) {
        if (r.chance(share)) out.push_back(i);
    }
    return out;
}

std::vector<ad::quantized_body> gather(const std::vector<ad::quantized_body>& state,
                                       const std::vector<std::uint32_t>& indices) {
    std::vector<ad::quantized_body> out;
    for (std::uint32_t i : indices) out.push_back(state[i]);
    return out;
}

}  // namespace

TEST_CASE("Shared encodings of many views decode exactly, against fresh, stale and no baselines",
          "[protocol][delta][property]") {
    rng r(20261122);
    std::vector<ad::quantized_body> state;
    for (std::uint32_t id = 1; id <= 1500; ++id) {
        if (r.chance(0.7)) state.push_back(ad::test::random_body(r, id));
    }
    struct kept {
        std::uint32_t tick;
        std::vector<ad::quantized_body> state;
    };
    std::deque<kept> history;
    std::uint32_t tick = 0;
    ad::shared_encoder encoder;
    std::vector<std::uint8_t> bytes;
    std::size_t deltas = 0, fulls = 0, removed_or_added = 0;
    for (int snapshot = 0; snapshot < 60; ++snapshot) {
        const auto ticks = static_cast<std::uint32_t>(1 + r.below(6));
        tick += ticks;
        ad::test::evolve(state, r, ticks, 60);
        // Every baseline the history still holds, and none.
        for (std::size_t back = 0; back <= history.size(); ++back) {
            const bool full = back == history.size();
            const kept* base = full ? nullptr : &history[history.size() - 1 - back];
            const ad::elapsed_time elapsed{full ? 0 : tick - base->tick, 60};
            encoder.prepare(state, full ? std::nullopt : std::optional<ad::view>(base->state), elapsed);
            for (int client = 0; client < 6; ++client) {
                const double share = client == 0 ? 1.0 : r.uniform(0.0, 1.0);
                const std::vector<std::uint32_t> current = random_view(r, state.size(), share);
                const std::vector<std::uint32_t> held =
                    full ? std::vector<std::uint32_t>{} : random_view(r, base->state.size(), r.uniform(0.0, 1.0));
                encoder.encode(current, held, bytes);
                const std::vector<ad::quantized_body> expected = gather(state, current);
                const std::vector<ad::quantized_body> baseline =
                    full ? std::vector<ad::quantized_body>{} : gather(base->state, held);
                const auto decoded =
                    ad::decode(bytes, full ? std::nullopt : std::optional<ad::view>(baseline), elapsed);
                INFO("snapshot " << snapshot << " back " << back << " client " << client << ": " << decoded.error);
                REQUIRE(decoded.ok());
                REQUIRE(decoded.value == expected);
                ++(full ? fulls : deltas);
                if (!full && expected.size() != baseline.size()) ++removed_or_added;
            }
        }
        history.push_back({tick, state});
        if (history.size() > 4) history.pop_front();
    }
    CHECK(deltas > 1000);
    CHECK(fulls == 60 * 6);
    CHECK(removed_or_added > 500);
}

TEST_CASE("A shared encoding is no larger than a few bytes over the per-view encoder's", "[protocol][delta]") {
    // The body fields' code orders come from the whole state, not the view: for views drawn
    // from the same state the sizes stay close.
    rng r(5);
    auto bodies = ad::test::make_bodies(r, ad::test::motion::player, 600, 400);
    const std::vector<ad::quantized_body> base = ad::test::quantize_view(bodies);
    for (int i = 0; i < 3; ++i) ad::test::step(bodies, r, 1.0f / 60);
    const std::vector<ad::quantized_body> now = ad::test::quantize_view(bodies);
    ad::shared_encoder encoder;
    encoder.prepare(now, ad::view(base), {3, 60});
    std::vector<std::uint8_t> shared;
    std::size_t shared_total = 0, plain_total = 0;
    for (int client = 0; client < 50; ++client) {
        const std::vector<std::uint32_t> view = random_view(r, now.size(), 0.2);
        encoder.encode(view, view, shared);
        const auto current = gather(now, view);
        const auto held = gather(base, view);
        shared_total += shared.size();
        plain_total += ad::encode(current, ad::view(held), {3, 60}).size();
        REQUIRE(ad::decode(shared, ad::view(held), {3, 60}).value == current);
    }
    CHECK(static_cast<double>(shared_total) <= 1.05 * static_cast<double>(plain_total) + 50 * 4);
}
