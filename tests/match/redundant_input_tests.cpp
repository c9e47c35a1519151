// Redundant inputs (Input.earlier) through match::receive(), as a transport drives it: earlier
// inputs are taken in order, each once, before the Input that carries them; malformed lists
// are refused with bad_input.
#include <catch2/catch.hpp>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "match/drive.hpp"
#include "protocol/decode.hpp"
#include "protocol/verify.hpp"
#include "server/world/presets.hpp"

using namespace arena;
using namespace arena::match_test;
using protocol::RejectCode;

namespace {

// Input n's thrust is n / 100: what the world applied tells which input it was.
protocol::input_msg input(uint32_t sequence, std::vector<uint32_t> earlier = {}) {
    protocol::input_msg in{sequence, static_cast<float>(sequence) / 100.0f, 0.0f, 0};
    for (uint32_t e : earlier) in.earlier.push_back({e, static_cast<float>(e) / 100.0f, 0.0f, 0});
    return in;
}

}  // namespace

TEST_CASE("earlier inputs are taken in order, each once, before the Input that carries them", "[match][udp]") {
    match::match m({}, rockless_asteroids());
    quiet_client c;
    REQUIRE(join(m, c, {protocol::protocol_version, "ann", ""}) != 0);
    m.tick();  // the join: the body enters the world
    std::vector<float> applied;
    m.on_tick = [&](const match::tick_record& r, uint64_t) {
        for (const auto& in : r.inputs) applied.push_back(in.input.thrust);
    };
    REQUIRE(send_input(m, c, input(1)));
    // 2 and 3 were lost; 4 repeats them (and 1, taken already).
    REQUIRE(send_input(m, c, input(4, {1, 2, 3})));
    // 3 arrives late, alone: stale. 6 repeats 5, which never came, and 4, taken already.
    REQUIRE(send_input(m, c, input(3)));
    REQUIRE(send_input(m, c, input(6, {4, 5})));
    for (int t = 0; t < 7; ++t) m.tick();
    std::string seen;
    for (float a : applied) seen += std::to_string(a) + " ";
    INFO(seen);
    REQUIRE(applied.size() == 7);
    const std::vector<float> expected = {0.01f, 0.02f, 0.03f, 0.04f, 0.05f, 0.06f, 0.06f};  // then an underrun
    CHECK(applied == expected);
    CHECK(m.counters().inputs_recovered == 3);  // 2, 3 and 5
    CHECK(m.counters().inputs_lost == 0);
    CHECK(m.counters().stale_inputs == 1);
    CHECK(m.counters().inputs_received == 4);  // messages: the rate limit counts these
    CHECK_FALSE(c.rejected);
}

TEST_CASE("inputs that neither came nor were repeated are counted lost", "[match][udp]") {
    match::match m({}, rockless_asteroids());
    quiet_client c;
    REQUIRE(join(m, c, {protocol::protocol_version, "ann", ""}) != 0);
    REQUIRE(send_input(m, c, input(1)));
    REQUIRE(send_input(m, c, input(5, {3, 4})));  // 2 is gone for good
    REQUIRE(send_input(m, c, input(9)));          // 6, 7 and 8 too (a client without earlier lists)
    REQUIRE(send_input(m, c, input(8)));          // late: stale, not found again
    CHECK(m.counters().inputs_lost == 4);
    CHECK(m.counters().inputs_recovered == 2);
    CHECK(m.counters().stale_inputs == 1);
}

TEST_CASE("an Input's earlier list out of order, too long or not finite is refused with bad_input", "[match][udp]") {
    struct bad_case {
        const char* what;
        protocol::input_msg in;
        const char* detail;
    };
    protocol::input_msg not_finite = input(5, {3, 4});
    not_finite.earlier[1].turn = std::numeric_limits<float>::infinity();
    const std::vector<bad_case> cases = {
        {"not rising", input(5, {3, 2}), "sequences must rise"},
        {"not below the Input's own", input(5, {4, 5}), "sequences must rise"},
        {"more than 8", input(20, {1, 2, 3, 4, 5, 6, 7, 8, 9}), "more than 8"},
        {"not finite", not_finite, "earlier input 4: turn is not a finite number"},
    };
    for (const bad_case& bad : cases) {
        INFO(bad.what);
        match::match m({}, rockless_asteroids());
        quiet_client c;
        REQUIRE(join(m, c, {protocol::protocol_version, "ann", ""}) != 0);
        CHECK_FALSE(send_input(m, c, bad.in));
        CHECK(c.rejected == RejectCode::bad_input);
        CHECK(c.detail.find(bad.detail) != std::string::npos);
    }
}

TEST_CASE("an Input with earlier inputs round-trips through the frame", "[protocol][udp]") {
    const protocol::input_msg sent = input(9, {6, 7, 8});
    const protocol::frame_bytes frame = protocol::encode_input(sent);
    std::vector<uint8_t> aligned(frame.begin(), frame.end());
    auto verified = protocol::verify_message(aligned, protocol::client_frame_limits);
    REQUIRE(verified);
    auto decoded = protocol::decode_input(*verified.value);
    REQUIRE(decoded);
    CHECK(decoded.value == sent);
    // Without earlier inputs the frame is what it was before the field existed.
    const protocol::frame_bytes plain = protocol::encode_input(input(9));
    CHECK(plain.size() < frame.size());
}
