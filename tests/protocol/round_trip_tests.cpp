// Every message type: encode, read back from a byte stream (whole, one byte at a time, and
// concatenated with the others), verify, decode, compare every field.
#include <catch2/catch.hpp>

#include <bit>
#include <limits>
#include <string>

#include "protocol/decode.hpp"
#include "protocol/messages.hpp"
#include "protocol/verify.hpp"
#include "protocol/version.hpp"
#include "stream.hpp"

namespace ap = arena::protocol;
using arena::protocol::test::read_stream;

namespace {

// Reads frame through a frame_reader with several chunkings, checks the bytes survive
// unchanged, and returns the verified message of the last reading (kept alive by storage).
const ap::Message* read_back(const ap::frame_bytes& frame, std::vector<std::uint8_t>& storage,
                             std::uint32_t max_body = ap::max_client_frame_body) {
    for (std::size_t chunk : {frame.size(), std::size_t{1}, std::size_t{3}, std::size_t{7}}) {
        const auto out = read_stream(frame, chunk, max_body);
        INFO("chunk " << chunk);
        REQUIRE(out.error.empty());
        REQUIRE(out.frames.size() == 1);
        REQUIRE(out.frames[0] == frame);
        REQUIRE(out.buffered == 0);
        storage = out.frames[0];
    }
    const auto verified = ap::verify_message(storage, {.max_body = max_body});
    INFO(verified.error);
    REQUIRE(verified);
    return verified.value;
}

}  // namespace

TEST_CASE("Hello round-trips every field", "[protocol]") {
    std::vector<std::uint8_t> storage;
    const auto frame = ap::encode_hello(ap::protocol_version, "bot-7 \xc3\xa9", "s3cret");
    const auto* m = read_back(frame, storage);
    CHECK(m->payload_type() == ap::Payload::Hello);
    const auto hello = ap::decode_hello(*m);
    REQUIRE(hello);
    CHECK(hello.value == ap::hello_msg{ap::protocol_version, "bot-7 \xc3\xa9", "s3cret"});
}

TEST_CASE("Hello's appended flags round-trip, and a spectator's Hello is a player's plus one field", "[protocol]") {
    std::vector<std::uint8_t> storage;
    const auto* m = read_back(ap::encode_hello(ap::protocol_version, "eye", "k", true, true), storage);
    const auto hello = ap::decode_hello(*m);
    REQUIRE(hello);
    CHECK(hello.value == ap::hello_msg{ap::protocol_version, "eye", "k", true, true});
    // Whether the table holds the field (generated tables derive privately from flatbuffers::Table).
    const auto written = [](const ap::Message* message) {
        return reinterpret_cast<const flatbuffers::Table*>(message->payload_as_Hello())
            ->CheckField(ap::Hello::VT_SPECTATOR);
    };
    CHECK(written(m));
    // false is the default and is not written: a player's Hello is the one it was before the field.
    std::vector<std::uint8_t> player_storage;
    const auto* player = read_back(ap::encode_hello(ap::protocol_version, "eye", "k", true, false), player_storage);
    CHECK_FALSE(written(player));
    CHECK_FALSE(ap::decode_hello(*player).value.spectator);
}

TEST_CASE("Hello with empty strings round-trips", "[protocol]") {
    std::vector<std::uint8_t> storage;
    const auto* m = read_back(ap::encode_hello(0xffff, {}, {}), storage);
    const auto hello = ap::decode_hello(*m);
    REQUIRE(hello);
    CHECK(hello.value == ap::hello_msg{0xffff, "", ""});
}

TEST_CASE("Welcome round-trips every field, including a large world_config", "[protocol]") {
    ap::welcome_info w;
    w.player_id = 0xfedcba98u;
    w.entity_id = 42;
    w.tick = 123456789;
    w.tick_rate = 60;
    w.snapshot_rate = 20;
    w.preset = "arena-small";
    w.world_config = "{\"gravity\": [0, -9.81], \"bodies\": [" + std::string(200000, ' ') + "]}";
    w.world_config_hash = 0x0123456789abcdefull;
    w.world_version = 7;
    std::vector<std::uint8_t> storage;
    // Bigger than a client frame may be: the client reads the server with the larger limit.
    const auto* m = read_back(ap::encode_welcome(w), storage, ap::max_server_frame_body);
    const auto welcome = ap::decode_welcome(*m);
    REQUIRE(welcome);
    CHECK(welcome.value == w);
}

TEST_CASE("Reject round-trips every code", "[protocol]") {
    for (const auto code : ap::EnumValuesRejectCode()) {
        std::vector<std::uint8_t> storage;
        const std::string reason = std::string("because ") + ap::EnumNameRejectCode(code);
        const auto* m = read_back(ap::encode_reject(code, reason), storage);
        const auto reject = ap::decode_reject(*m);
        REQUIRE(reject);
        CHECK(reject.value == ap::reject_msg{code, reason});
    }
}

TEST_CASE("Input round-trips bit for bit", "[protocol]") {
    const ap::input_msg inputs[] = {
        {1, 1.0f, -1.0f, ap::button_impulse},
        {0xffffffffu, std::numeric_limits<float>::lowest(), std::numeric_limits<float>::denorm_min(), 0xff},
        {77, 0.1f, 0.3333333f, 0},
    };
    for (const auto& in : inputs) {
        std::vector<std::uint8_t> storage;
        const auto* m = read_back(ap::encode_input(in), storage);
        const auto decoded = ap::decode_input(*m);
        REQUIRE(decoded);
        CHECK(decoded.value.sequence == in.sequence);
        CHECK(std::bit_cast<std::uint32_t>(decoded.value.thrust) == std::bit_cast<std::uint32_t>(in.thrust));
        CHECK(std::bit_cast<std::uint32_t>(decoded.value.turn) == std::bit_cast<std::uint32_t>(in.turn));
        CHECK(decoded.value.buttons == in.buttons);
    }
}

TEST_CASE("Input -0.0 reads back as +0.0: a table scalar equal to its default is omitted", "[protocol]") {
    // Documented in README.md; harmless for controls. BodyState, a struct, keeps -0.0.
    std::vector<std::uint8_t> storage;
    const auto frame = ap::encode_input({3, -0.0f, -0.0f, 0});
    const auto decoded = ap::decode_input(*read_back(frame, storage));
    REQUIRE(decoded);
    CHECK(std::bit_cast<std::uint32_t>(decoded.value.thrust) == 0u);
    CHECK(std::bit_cast<std::uint32_t>(decoded.value.turn) == 0u);
}

TEST_CASE("Ping, Pong and Bye round-trip", "[protocol]") {
    std::vector<std::uint8_t> storage;
    const auto ping = ap::decode_ping(*read_back(ap::encode_ping(0x8000000000000001ull), storage));
    REQUIRE(ping);
    CHECK(ping.value.client_time == 0x8000000000000001ull);

    const auto pong = ap::decode_pong(*read_back(ap::encode_pong(99, 0xabcdef01u), storage));
    REQUIRE(pong);
    CHECK(pong.value == ap::pong_msg{99, 0xabcdef01u, {}});  // no hold: not measured
    // The server's hold of the Ping (appended to Pong): 0 is a measured hold, not an absent one.
    for (const std::uint32_t hold : {0u, 16'500u}) {
        const auto held = ap::decode_pong(*read_back(ap::encode_pong(99, 7, hold), storage));
        REQUIRE(held);
        CHECK(held.value == ap::pong_msg{99, 7, hold});
    }

    const auto bye = ap::decode_bye(*read_back(ap::encode_bye("server restart"), storage));
    REQUIRE(bye);
    CHECK(bye.value.reason == "server restart");
}

TEST_CASE("Frames concatenated in one stream come out in order, however it is split", "[protocol]") {
    std::vector<std::vector<std::uint8_t>> frames = {
        ap::encode_hello(1, "a", "b"),
        ap::encode_input({5, 0.5f, -0.25f, 1}),
        ap::encode_ping(3),
        ap::encode_pong(3, 4),
        ap::encode_reject(ap::RejectCode::rate_limit, "slow down"),
        ap::encode_bye("done"),
    };
    const auto stream = arena::protocol::test::concat(frames);
    for (std::size_t chunk :
         {stream.size(), std::size_t{1}, std::size_t{2}, std::size_t{5}, std::size_t{13}, std::size_t{64}}) {
        INFO("chunk " << chunk);
        const auto out = read_stream(stream, chunk);
        REQUIRE(out.error.empty());
        REQUIRE(out.frames == frames);
        CHECK(out.consumed == stream.size());
        for (const auto& f : out.frames) CHECK(ap::verify_message(f));
    }
    const auto out = read_stream(stream, stream.size());
    CHECK(ap::decode_input(*ap::verify_message(out.frames[1]).value).value == ap::input_msg{5, 0.5f, -0.25f, 1});
    CHECK(ap::decode_reject(*ap::verify_message(out.frames[4]).value).value.code == ap::RejectCode::rate_limit);
}

TEST_CASE("A decoder refuses a message of another type, naming both", "[protocol]") {
    const auto frame = ap::encode_ping(1);
    const auto verified = ap::verify_message(frame);
    REQUIRE(verified);
    const auto hello = ap::decode_hello(*verified.value);
    REQUIRE_FALSE(hello);
    CHECK(hello.error == "expected Hello, got Ping");
    CHECK_FALSE(ap::decode_snapshot(*verified.value));
}

// Whether an Input's numbers are finite is asked once, at admission (tests/match/): the
// decoder hands them on as sent, bit for bit.
TEST_CASE("Input decoding hands a non-finite thrust or turn on as sent, for admission to refuse", "[protocol]") {
    const float odd[] = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                         -std::numeric_limits<float>::infinity()};
    for (const float f : odd) {
        const auto thrust = ap::decode_input(*ap::verify_message(ap::encode_input({1, f, 0.0f, 0})).value);
        REQUIRE(thrust);
        CHECK(std::bit_cast<uint32_t>(thrust.value.thrust) == std::bit_cast<uint32_t>(f));

        const auto turn = ap::decode_input(*ap::verify_message(ap::encode_input({1, 0.0f, f, 0})).value);
        REQUIRE(turn);
        CHECK(std::bit_cast<uint32_t>(turn.value.turn) == std::bit_cast<uint32_t>(f));
    }
}
