// Lag compensation at the match (docs/LAG_COMPENSATION.md): each input's view moment
// (Input.view_tick and view_fraction) becomes the rewind the world's rules get, clamped to
// --lag-compensation-ms and never of the future; an earlier input's view is a tick older per
// sequence; a cheater claiming an older view gains nothing beyond the cap.
#include <catch2/catch.hpp>
#include <optional>
#include <string>
#include <vector>

#include "match/drive.hpp"
#include "server/world/presets.hpp"

using namespace arena;
using namespace arena::match_test;

namespace {

// The rewinds the world got for one player's inputs, one a tick, after the inputs `sent`
// (sequences 1, 2... from `first_tick` on) each made from the view `view_of(sequence)`.
struct rewinds {
    std::vector<uint16_t> applied;
    uint32_t first_tick = 0;
};

rewinds run(uint32_t lag_compensation_ms, uint32_t inputs, uint64_t (*view_of)(uint32_t tick, uint32_t sequence)) {
    match::match_config config;
    config.lag_compensation_ms = lag_compensation_ms;
    match::match m(config, rockless_asteroids());
    quiet_client c;
    REQUIRE(join(m, c, {protocol::protocol_version, "ann", ""}) != 0);
    for (int t = 0; t < 100; ++t) m.tick();  // a world tick of 100: views up to 100 ticks back exist
    rewinds out;
    out.first_tick = m.state().tick();
    m.on_tick = [&](const match::tick_record& r, uint64_t) {
        for (const auto& in : r.inputs) out.applied.push_back(in.input.rewind);
    };
    for (uint32_t s = 1; s <= inputs; ++s) {
        protocol::input_msg in{s, 0.0f, 0.0f, 0};
        const uint64_t view = view_of(m.state().tick(), s);
        in.view_tick = static_cast<uint32_t>(view / 256);
        in.view_fraction = static_cast<uint8_t>(view % 256);
        REQUIRE(send_input(m, c, in));
        m.tick();
    }
    return out;
}

}  // namespace

TEST_CASE("an input's view moment becomes its rewind, to the 1/256 of a tick", "[match][lag]") {
    // Each input made from a view 6.5 ticks behind the tick it is applied in.
    const rewinds r = run(250, 5, [](uint32_t tick, uint32_t) { return uint64_t{tick} * 256 - 6 * 256 - 128; });
    CHECK(r.applied == std::vector<uint16_t>(5, 6 * 256 + 128));
}

TEST_CASE("a view of the future is judged against the present, and none told too", "[match][lag]") {
    CHECK(run(250, 3, [](uint32_t tick, uint32_t) { return uint64_t{tick + 10} * 256; }).applied ==
          std::vector<uint16_t>(3, 0));
    CHECK(run(250, 3, [](uint32_t, uint32_t) { return uint64_t{0}; }).applied == std::vector<uint16_t>(3, 0));
}

TEST_CASE("a claim older than --lag-compensation-ms gains nothing beyond it, and 0 turns it off", "[match][lag]") {
    // 250 ms at 60 Hz: 15 ticks. A cheater claiming to see 90 ticks back is rewound 15.
    const auto ninety_back = [](uint32_t tick, uint32_t) {
        return uint64_t{tick} * 256 - 90 * 256;
    };
    CHECK(run(250, 3, ninety_back).applied == std::vector<uint16_t>(3, 15 * 256));
    CHECK(run(1000, 3, ninety_back).applied == std::vector<uint16_t>(3, 60 * 256));
    // More than the history games keep (world::max_rewind, 64 ticks) is never given.
    CHECK(run(5000, 3, ninety_back).applied == std::vector<uint16_t>(3, world::max_rewind));
    CHECK(run(0, 3, ninety_back).applied == std::vector<uint16_t>(3, 0));
}
