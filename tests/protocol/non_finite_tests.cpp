// NaN never reaches the wire: the snapshot encoders write non-finite values as 0 and count
// them, and a client refuses a snapshot that carries one anyway.
#include <catch2/catch.hpp>
#include <limits>
#include <vector>

#include "protocol/decode.hpp"
#include "protocol/messages.hpp"
#include "protocol/snapshot.hpp"
#include "protocol/verify.hpp"

namespace ap = arena::protocol;

namespace {

constexpr float not_a_number = std::numeric_limits<float>::quiet_NaN();
constexpr float infinity = std::numeric_limits<float>::infinity();

ap::result<ap::snapshot_view> decode(std::span<const std::uint8_t> span, std::vector<std::uint8_t>& frame) {
    frame.assign(span.begin(), span.end());
    const auto verified = ap::verify_message(frame, ap::server_frame_limits);
    REQUIRE(verified);
    return ap::decode_snapshot(*verified.value);
}

}  // namespace

TEST_CASE("snapshot encoders write NaN and infinities as 0 and count them", "[protocol][nan]") {
    const std::vector<ap::BodyState> bodies{{1, 0, 1.5f, 2.5f, 0, 0, 0, 0},
                                            {7, 3, not_a_number, 4.0f, 0, -infinity, 0.5f, infinity}};
    const std::uint64_t before = ap::non_finite_values_replaced();
    std::vector<std::uint8_t> frame;

    flatbuffers::FlatBufferBuilder fbb;
    const auto decoded = decode(ap::encode_snapshot(fbb, 10, 0, bodies), frame);
    REQUIRE(decoded);
    REQUIRE(decoded.value.bodies.size() == 2);
    const ap::BodyState& b = decoded.value.bodies[1];
    CHECK(b.id() == 7);
    CHECK(b.x() == 0.0f);
    CHECK(b.y() == 4.0f);
    CHECK(b.vy() == 0.0f);
    CHECK(b.angle() == 0.5f);
    CHECK(b.angular_velocity() == 0.0f);
    CHECK(decoded.value.bodies[0].x() == 1.5f);  // healthy bodies untouched
    CHECK(ap::non_finite_values_replaced() == before + 3);

    ap::snapshot_encoder shared;
    shared.build(11, bodies);
    const auto again = decode(shared.frame_with_ack(5), frame);
    REQUIRE(again);
    CHECK(ap::non_finite_field(again.value.bodies[1]) == nullptr);
    CHECK(ap::non_finite_values_replaced() == before + 6);
}

TEST_CASE("a client refuses a snapshot with a non-finite value, naming the body and field", "[protocol][nan]") {
    // Bytes a broken (or hostile) server could send: built without the encoders' guard.
    const std::vector<ap::BodyState> bodies{{1, 0, 1, 1, 0, 0, 0, 0}, {9, 2, 3, 4, 5, not_a_number, 0, 0}};
    flatbuffers::FlatBufferBuilder fbb;
    const auto vector = fbb.CreateVectorOfStructs(bodies.data(), bodies.size());
    ap::finish_message(fbb, ap::Payload::Snapshot, ap::CreateSnapshot(fbb, 3, 0, vector).Union());
    std::vector<std::uint8_t> frame;
    const auto decoded = decode({fbb.GetBufferPointer(), fbb.GetSize()}, frame);
    REQUIRE_FALSE(decoded);
    CHECK(decoded.error == "body 9 has a non-finite vy");
}
