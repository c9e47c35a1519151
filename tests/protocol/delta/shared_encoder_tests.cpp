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

TEST_CASE("Encodings of part of a view: chosen bodies exact, the baseline's others kept as predicted",
          "[protocol][delta][property]") {
    // One client over many snapshots, each holding a random part of a random view: what it
    // decodes must be exactly what encode_chosen() says it now holds, chained from one
    // snapshot to the next through the held bodies (decoded against the previous result).
    rng r(20261201);
    std::vector<ad::quantized_body> state;
    for (std::uint32_t id = 1; id <= 400; ++id) {
        if (r.chance(0.8)) state.push_back(ad::test::random_body(r, id));
    }
    ad::shared_encoder encoder;
    std::vector<std::uint8_t> bytes;
    std::vector<std::uint32_t> sent;
    std::vector<ad::shared_encoder::held_body> held;
    // What the client holds: its view (indices into `prev`), those at other states, and prev.
    std::vector<ad::quantized_body> prev;
    std::vector<std::uint32_t> holds_view;
    std::vector<ad::shared_encoder::held_body> holds_other;
    std::vector<ad::quantized_body> client;  // the decoded view
    std::size_t kept = 0, refreshed_from_held = 0;
    for (int snapshot = 0; snapshot < 80; ++snapshot) {
        const bool full = snapshot % 20 == 0;  // now and then the client lost its baseline
        ad::test::evolve(state, r, 3, 60);
        const ad::elapsed_time elapsed{full ? 0u : 3u, 60};
        encoder.prepare(state, full ? std::nullopt : std::optional<ad::view>(prev), elapsed);
        const std::vector<std::uint32_t> current = random_view(r, state.size(), r.uniform(0.5, 1.0));
        std::vector<std::uint8_t> chosen(current.size());
        const double share = r.uniform(0.0, 1.0);
        for (auto& c : chosen) c = r.chance(share) ? 1 : 0;
        encoder.encode_chosen(current, chosen, full ? std::span<const std::uint32_t>() : holds_view,
                              full ? std::span<const ad::shared_encoder::held_body>() : holds_other, sent, held, bytes);
        const auto decoded = ad::decode(bytes, full ? std::nullopt : std::optional<ad::view>(client), elapsed);
        INFO("snapshot " << snapshot << ": " << decoded.error);
        REQUIRE(decoded.ok());
        // Expected: the sent view at this state, except the held bodies.
        std::vector<ad::quantized_body> expected;
        std::size_t h = 0;
        for (const std::uint32_t i : sent) {
            while (h < held.size() && held[h].index < i) ++h;
            expected.push_back(h < held.size() && held[h].index == i ? held[h].state : state[i]);
        }
        REQUIRE(decoded.value == expected);
        // Every chosen body is there at this state; every other one is either kept (it was in
        // the client's view) or absent (new to it): never half-way.
        for (std::size_t k = 0; k < current.size(); ++k) {
            const auto at = std::ranges::find(sent, current[k]);
            if (chosen[k]) {
                REQUIRE(at != sent.end());
                REQUIRE(std::ranges::find(held, current[k], &ad::shared_encoder::held_body::index) == held.end());
                if (!full && std::ranges::find(holds_other, state[current[k]].id,
                                               [&](const auto& o) { return o.state.id; }) != holds_other.end())
                    ++refreshed_from_held;
            } else if (at != sent.end()) {
                REQUIRE(std::ranges::find(client, state[current[k]].id, &ad::quantized_body::id) != client.end());
                ++kept;
            }
        }
        client = decoded.value;
        prev = state;
        holds_view = sent;
        holds_other = held;
    }
    CHECK(kept > 1000);
    CHECK(refreshed_from_held > 100);
}

TEST_CASE("A view encoded again gets the same bytes as a fresh encoder gives it, in any order of views",
          "[protocol][delta]") {
    rng r(20261201);
    std::vector<ad::quantized_body> base;
    for (std::uint32_t id = 1; id <= 400; ++id) base.push_back(ad::test::random_body(r, id));
    std::vector<ad::quantized_body> state = base;
    ad::test::evolve(state, r, 3, 60);
    const ad::elapsed_time elapsed{3, 60};
    const std::vector<std::uint32_t> all = random_view(r, state.size(), 1.0);
    const std::vector<std::uint32_t> some = random_view(r, state.size(), 0.5);
    const std::vector<std::uint32_t> held_all = random_view(r, base.size(), 1.0);
    const std::vector<std::uint32_t> held_some = random_view(r, base.size(), 0.5);
    struct call {
        const std::vector<std::uint32_t>* current;
        const std::vector<std::uint32_t>* held;
    };
    // Repeats, a change of only the current view, of only the held one, and back.
    const std::vector<call> calls = {{&all, &held_all},  {&all, &held_all},   {&some, &held_all},
                                     {&some, &held_all}, {&some, &held_some}, {&all, &held_all}};
    for (const bool with_baseline : {true, false}) {
        const std::optional<ad::view> baseline = with_baseline ? std::optional<ad::view>(base) : std::nullopt;
        ad::shared_encoder reused;
        reused.prepare(state, baseline, elapsed);
        std::vector<std::uint8_t> bytes, fresh_bytes;
        for (std::size_t n = 0; n < calls.size(); ++n) {
            reused.encode(*calls[n].current, *calls[n].held, bytes);
            ad::shared_encoder fresh;
            fresh.prepare(state, baseline, elapsed);
            fresh.encode(*calls[n].current, *calls[n].held, fresh_bytes);
            INFO("baseline " << with_baseline << " call " << n);
            REQUIRE(bytes == fresh_bytes);
        }
        // A new preparation forgets the last encoding: the same views against another state.
        std::vector<ad::quantized_body> later = state;
        ad::test::evolve(later, r, 2, 60);
        reused.prepare(later, baseline, {5, 60});
        reused.encode(all, held_all, bytes);
        ad::shared_encoder fresh;
        fresh.prepare(later, baseline, {5, 60});
        fresh.encode(all, held_all, fresh_bytes);
        REQUIRE(bytes == fresh_bytes);
    }
}
