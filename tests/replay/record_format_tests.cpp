// Every record type round-trips through encode and decode with every field intact.
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "protocol/replay_generated.h"
#include "server/replay/record_format.hpp"
#include "server/world/little_endian.hpp"

using namespace arena;
using namespace arena::replay;

namespace {

// One record's bytes from the encoder: checks the checksum and returns prefix + body in
// 8-byte aligned storage, as the reader hands it to decode_record.
struct aligned_frame {
    std::vector<uint64_t> words;
    size_t size = 0;
    std::span<const uint8_t> span() const { return {reinterpret_cast<const uint8_t*>(words.data()), size}; }
};

aligned_frame frame_of(const std::vector<uint8_t>& bytes) {
    REQUIRE(bytes.size() >= record_prefix_size + min_record_body + record_checksum_size);
    aligned_frame f;
    f.size = bytes.size() - record_checksum_size;
    f.words.resize((bytes.size() + 7) / 8);
    std::memcpy(f.words.data(), bytes.data(), bytes.size());
    CHECK(world::load_le32(bytes.data() + f.size) == record_checksum(f.span().subspan(record_prefix_size)));
    CHECK(world::load_le32(bytes.data()) == f.size - record_prefix_size);
    return f;
}

template <class T>
T round_trip(const T& in) {
    record_encoder encoder;
    std::vector<uint8_t> bytes;
    encoder.append(in, bytes);
    const aligned_frame f = frame_of(bytes);
    auto decoded = decode_record(f.span());
    INFO(decoded.error);
    REQUIRE(decoded.ok());
    REQUIRE(std::holds_alternative<T>(decoded.value));
    return std::get<T>(decoded.value);
}

}  // namespace

TEST_CASE("a Header round-trips with every field", "[replay]") {
    header h;
    h.format_version = 1;
    h.protocol_version = 7;
    h.world_version = 3;
    h.world_config = R"({"preset": "asteroids"})";
    h.preset = "asteroids";
    h.seed = 0x0123456789abcdefULL;
    h.tick_rate = 30;
    h.hash_interval = 15;
    h.start_tick = 1234;
    h.start_hash = 0xfedcba9876543210ULL;
    const header out = round_trip(h);
    CHECK(out.format_version == h.format_version);
    CHECK(out.protocol_version == h.protocol_version);
    CHECK(out.world_version == h.world_version);
    CHECK(out.world_config == h.world_config);
    CHECK(out.preset == h.preset);
    CHECK(out.seed == h.seed);
    CHECK(out.tick_rate == h.tick_rate);
    CHECK(out.hash_interval == h.hash_interval);
    CHECK(out.start_tick == h.start_tick);
    CHECK(out.start_hash == h.start_hash);
}

TEST_CASE("a Tick round-trips with joins, leaves and the exact bits of every input", "[replay]") {
    match::tick_record t;
    t.tick = 99;
    t.joins = {world::player_id{4}, world::player_id{9}};
    t.leaves = {world::body_id{2}};
    t.inputs = {{world::body_id{3}, {-0.0f, 0.25f, world::button_impulse}},
                {world::body_id{7}, {1.0f, -1.0f, 0}},
                {world::body_id{8}, {0.1f, 0.0f, 0}}};
    const match::tick_record out = round_trip(t);
    CHECK(out.tick == 99);
    CHECK(out.joins == t.joins);
    CHECK(out.leaves == t.leaves);
    REQUIRE(out.inputs.size() == t.inputs.size());
    for (size_t i = 0; i < t.inputs.size(); ++i) {
        CHECK(out.inputs[i].body_id == t.inputs[i].body_id);
        // Bits, not values: -0.0 must stay -0.0 (the world's hash tells them apart).
        CHECK(std::bit_cast<uint32_t>(out.inputs[i].input.thrust) == std::bit_cast<uint32_t>(t.inputs[i].input.thrust));
        CHECK(std::bit_cast<uint32_t>(out.inputs[i].input.turn) == std::bit_cast<uint32_t>(t.inputs[i].input.turn));
        CHECK(out.inputs[i].input.buttons == t.inputs[i].input.buttons);
    }
}

TEST_CASE("a Tick's join names round-trip, and a tick without them replays nameless", "[replay]") {
    match::tick_record t;
    t.tick = 12;
    t.joins = {world::player_id{4}, world::player_id{9}};
    t.join_names = {"ada", "Grace Hopper \xc3\xa9"};
    CHECK(round_trip(t).join_names == t.join_names);
    t.join_names.clear();  // a tick as recordings before names were recorded hold it
    const match::tick_record old = round_trip(t);
    CHECK(old.joins == t.joins);
    CHECK(old.join_names.empty());
}

namespace {

// A Tick record with `joins` and `names` as given, whatever their counts.
std::vector<uint8_t> tick_with_names(const std::vector<uint32_t>& joins, const std::vector<std::string>& names) {
    namespace fb = protocol::replay;
    flatbuffers::FlatBufferBuilder b;
    const auto j = b.CreateVector(joins);
    const auto n = b.CreateVectorOfStrings(names);
    fb::TickBuilder tick(b);
    tick.add_tick(7);
    tick.add_joins(j);
    tick.add_join_names(n);
    const auto content = tick.Finish();
    fb::FinishSizePrefixedRecordBuffer(b, fb::CreateRecord(b, fb::Content::Tick, content.Union()));
    std::vector<uint8_t> bytes(b.GetBufferPointer(), b.GetBufferPointer() + b.GetSize());
    world::append_le32(bytes, record_checksum({bytes.data() + record_prefix_size, bytes.size() - record_prefix_size}));
    return bytes;
}

}  // namespace

TEST_CASE("a Tick whose join names do not match its joins, or forge a log line, is refused", "[replay]") {
    const aligned_frame counts = frame_of(tick_with_names({1, 2}, {"ada"}));
    const auto a = decode_record(counts.span());
    CHECK_FALSE(a.ok());
    CHECK(a.error == "Tick 7: 1 join names for 2 joins");
    const aligned_frame forged = frame_of(tick_with_names({1}, {"ada\nleave player=2"}));
    const auto b = decode_record(forged.span());
    CHECK_FALSE(b.ok());
    CHECK_THAT(b.error, Catch::StartsWith("Tick 7: join name 0: ") && Catch::Contains("control character"));
    CHECK(decode_record(frame_of(tick_with_names({1}, {"ada"})).span()).ok());
}

TEST_CASE("a Tick's rewinds round-trip, and a tick without them rewinds nothing", "[replay][lag]") {
    match::tick_record t;
    t.tick = 40;
    t.inputs = {{world::body_id{3}, {0, 0, 2}}, {world::body_id{7}, {0, 0, 0}}};
    t.inputs[0].input.rewind = 6 * 256 + 128;  // lag compensation: 6.5 ticks back
    const match::tick_record out = round_trip(t);
    REQUIRE(out.inputs.size() == 2);
    CHECK(out.inputs[0].input.rewind == 6 * 256 + 128);
    CHECK(out.inputs[1].input.rewind == 0);
    t.inputs[0].input.rewind = 0;
    CHECK(round_trip(t).inputs[0].input.rewind == 0);
    // Over the most a match gives: a forged file, refused.
    t.inputs[0].input.rewind = world::max_rewind + 1;
    record_encoder encoder;
    std::vector<uint8_t> bytes;
    encoder.append(t, bytes);
    const aligned_frame f = frame_of(bytes);
    const auto decoded = decode_record(f.span());
    REQUIRE_FALSE(decoded.ok());
    CHECK(decoded.error == "Tick 40: input for body 3: rewind 16385 over the most, 16384");
}

TEST_CASE("an empty Tick round-trips", "[replay]") {
    const match::tick_record out = round_trip(match::tick_record{5, {}, {}, {}, {}});
    CHECK(out.tick == 5);
    CHECK(out.joins.empty());
    CHECK(out.leaves.empty());
    CHECK(out.inputs.empty());
}

TEST_CASE("Hash and End records round-trip", "[replay]") {
    const hash_check c = round_trip(hash_check{120, 0x8000000000000001ULL});
    CHECK(c.tick == 120);
    CHECK(c.hash == 0x8000000000000001ULL);
    const end_marker e = round_trip(end_marker{600, 42});
    CHECK(e.tick == 600);
    CHECK(e.hash == 42);
}

TEST_CASE("a Tick with a non-finite input is refused: NaN never enters the world", "[replay]") {
    record_encoder encoder;
    std::vector<uint8_t> bytes;
    match::tick_record t{3, {}, {}, {{world::body_id{5}, {std::numeric_limits<float>::quiet_NaN(), 0, 0}}}, {}};
    encoder.append(t, bytes);
    const aligned_frame f = frame_of(bytes);
    const auto decoded = decode_record(f.span());
    CHECK_FALSE(decoded.ok());
    CHECK_THAT(decoded.error, Catch::Contains("Tick 3: input for body 5"));
}

TEST_CASE("the record checksum is FNV-1a 32", "[replay]") {
    const auto of = [](std::string_view s) {
        return record_checksum({reinterpret_cast<const uint8_t*>(s.data()), s.size()});
    };
    // The published FNV-1a 32 test vectors.
    CHECK(of("") == 0x811c9dc5u);
    CHECK(of("a") == 0xe40c292cu);
    CHECK(of("foobar") == 0xbf9cf968u);
}
