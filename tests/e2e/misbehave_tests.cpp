// Fault frames do what their names say when they reach a reader with the server's limits,
// and the frames bots send every tick decode back.
#include <catch2/catch.hpp>
#include <cmath>

#include "client_sim/misbehave.hpp"
#include "client_sim/wire.hpp"
#include "protocol/decode.hpp"
#include "protocol/framing.hpp"
#include "protocol/verify.hpp"
#include "server/world/input.hpp"

using namespace arena::bots;
namespace protocol = arena::protocol;

TEST_CASE("garbage frames pass the length check and fail verification", "[bots][misbehave]") {
    arena::world::rng rng(99);
    for (int i = 0; i < 200; ++i) {
        const auto frame = garbage_frame(rng);
        protocol::frame_reader reader;  // the server's limits
        REQUIRE(reader.feed(frame) == frame.size());
        REQUIRE(reader.has_frame());
        REQUIRE_FALSE(protocol::verify_message(reader.frame()).ok());
    }
}

TEST_CASE("an oversize prefix is refused from its 4 bytes", "[bots][misbehave]") {
    protocol::frame_reader reader;
    reader.feed(oversize_prefix());
    CHECK(reader.failed());
    CHECK(std::string(reader.error()).find("exceeds") != std::string::npos);
}

TEST_CASE("half a frame never completes one", "[bots][misbehave]") {
    const auto frame = protocol::encode_input({1, 0.5f, 0.0f, 0});
    const auto half = half_frame(frame);
    REQUIRE(half.size() < frame.size());
    protocol::frame_reader reader;
    CHECK(reader.feed(half) == half.size());
    CHECK_FALSE(reader.has_frame());
    CHECK_FALSE(reader.failed());
}

TEST_CASE("a share of the bots misbehaves, spread over the indices", "[bots][misbehave]") {
    CHECK(misbehaving_count(100, 0.1) == 10);
    CHECK(misbehaving_count(5, 0.1) == 1);  // at least one
    CHECK(misbehaving_count(10, 0.0) == 0);
    CHECK(misbehaving_count(10, 1.0) == 10);
    for (std::uint32_t bots : {1u, 7u, 20u, 1000u}) {
        for (double share : {0.0, 0.05, 0.25, 0.5, 1.0}) {
            std::uint32_t chosen = 0;
            for (std::uint32_t i = 0; i < bots; ++i) chosen += is_misbehaving(i, bots, share) ? 1 : 0;
            CHECK(chosen == misbehaving_count(bots, share));
        }
    }
    // Evenly spread: with a quarter, one in every four consecutive bots.
    for (std::uint32_t start = 0; start < 20; start += 4) {
        int in_block = 0;
        for (std::uint32_t i = start; i < start + 4; ++i) in_block += is_misbehaving(i, 20, 0.25) ? 1 : 0;
        CHECK(in_block == 1);
    }
    CHECK(parse_misbehavior("slow-reader") == misbehavior::slow_reader);
    CHECK(to_string(misbehavior::abrupt_close) == "abrupt-close");
    CHECK_FALSE(parse_misbehavior("polite").has_value());
}

TEST_CASE("inputs and pings appended with the shared builder decode back", "[bots][wire]") {
    flatbuffers::FlatBufferBuilder fbb(64);
    std::vector<std::uint8_t> out;
    append_input(fbb, {7, 0.25f, -1.0f, 1}, out);
    append_ping(fbb, 0x0102030405060708ULL, out);
    append_input(fbb, {8, std::nanf(""), 0.0f, 0}, out);

    protocol::frame_reader reader;
    std::span<const std::uint8_t> rest(out);
    std::vector<protocol::Payload> seen;
    while (!rest.empty()) {
        rest = rest.subspan(reader.feed(rest));
        REQUIRE(reader.has_frame());
        const auto message = protocol::verify_message(reader.frame());
        REQUIRE(message.ok());
        seen.push_back(message.value->payload_type());
        if (seen.size() == 1)
            CHECK(protocol::decode_input(*message.value).value == protocol::input_msg{7, 0.25f, -1.0f, 1});
        if (seen.size() == 2) CHECK(protocol::decode_ping(*message.value).value.client_time == 0x0102030405060708ULL);
        // The NaN input is well formed and decodes as sent: admission is what refuses it
        // (world::check_input, the one check of an Input's numbers).
        if (seen.size() == 3) {
            const auto nan = protocol::decode_input(*message.value);
            REQUIRE(nan.ok());
            CHECK(std::isnan(nan.value.thrust));
            CHECK(arena::world::check_input({nan.value.thrust, nan.value.turn, nan.value.buttons}) ==
                  "thrust is not a finite number");
        }
        reader.next();
    }
    CHECK(seen.size() == 3);
}
