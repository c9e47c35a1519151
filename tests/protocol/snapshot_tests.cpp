// Snapshots: exact round trips at 0 and 1000 bodies, builder reuse, per-client ack patching.
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstring>
#include <vector>

#include "protocol/decode.hpp"
#include "protocol/snapshot.hpp"
#include "protocol/verify.hpp"
#include "stream.hpp"

namespace ap = arena::protocol;

namespace {

// Values that stress exact float transport: negative zero, denormals, huge, tiny, odd bits.
std::vector<ap::BodyState> make_bodies(std::size_t n) {
    std::vector<ap::BodyState> bodies;
    bodies.reserve(n);
    std::uint32_t bits = 0x3f800001u;
    auto next_float = [&bits] {
        bits = bits * 1664525u + 1013904223u;
        float f = std::bit_cast<float>(bits);
        return std::isfinite(f) ? f : -0.0f;
    };
    for (std::size_t i = 0; i < n; ++i) {
        const float x = next_float();
        const float y = next_float();
        const float vx = next_float();
        const float vy = next_float();
        const float angle = next_float();
        const float w = next_float();
        bodies.emplace_back(static_cast<std::uint32_t>(i + 1), static_cast<std::uint32_t>(i % 7), x, y, vx, vy, angle,
                            w);
    }
    return bodies;
}

bool same_bits(const ap::BodyState& a, const ap::BodyState& b) {
    auto bits = [](float f) {
        return std::bit_cast<std::uint32_t>(f);
    };
    return a.id() == b.id() && a.owner() == b.owner() && bits(a.x()) == bits(b.x()) && bits(a.y()) == bits(b.y()) &&
           bits(a.vx()) == bits(b.vx()) && bits(a.vy()) == bits(b.vy()) && bits(a.angle()) == bits(b.angle()) &&
           bits(a.angular_velocity()) == bits(b.angular_velocity());
}

ap::snapshot_view read_snapshot(const std::vector<std::uint8_t>& frame) {
    const auto verified = ap::verify_message(frame, ap::server_frame_limits);
    INFO(verified.error);
    REQUIRE(verified);
    const auto view = ap::decode_snapshot(*verified.value);
    REQUIRE(view);
    return view.value;
}

}  // namespace

TEST_CASE("BodyState is the 32-byte wire struct", "[protocol]") {
    STATIC_REQUIRE(sizeof(ap::BodyState) == 32);
    STATIC_REQUIRE(alignof(ap::BodyState) == 4);
}

TEST_CASE("A snapshot with 0 and with 1000 bodies round-trips bit for bit", "[protocol]") {
    for (const std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{1000}}) {
        INFO("bodies " << n);
        const auto bodies = make_bodies(n);
        flatbuffers::FlatBufferBuilder fbb;
        const auto span = ap::encode_snapshot(fbb, 0xdeadbeefu, 0x01020304u, bodies);
        const std::vector<std::uint8_t> frame(span.begin(), span.end());

        // Through the stream reader, whole and byte by byte, with the client's (server) limit.
        for (const std::size_t chunk : {frame.size(), std::size_t{1}}) {
            const auto out = arena::protocol::test::read_stream(frame, chunk, ap::max_server_frame_body);
            REQUIRE(out.frames.size() == 1);
            REQUIRE(out.frames[0] == frame);
        }

        const auto view = read_snapshot(frame);
        CHECK(view.tick == 0xdeadbeefu);
        CHECK(view.ack_sequence == 0x01020304u);
        REQUIRE(view.bodies.size() == n);
        for (std::size_t i = 0; i < n; ++i) {
            INFO("body " << i);
            REQUIRE(same_bits(view.bodies[i], bodies[i]));
        }
        // The bodies are one contiguous copy of the input array.
        if (n > 0) CHECK(std::memcmp(view.bodies.data(), bodies.data(), n * 32) == 0);
    }
}

TEST_CASE("A reused builder produces the same bytes as a fresh one", "[protocol]") {
    const auto big = make_bodies(1000);
    const auto small = make_bodies(3);
    flatbuffers::FlatBufferBuilder reused;
    (void)ap::encode_snapshot(reused, 1, 1, big);
    const auto again = ap::encode_snapshot(reused, 2, 9, small);
    flatbuffers::FlatBufferBuilder fresh;
    const auto once = ap::encode_snapshot(fresh, 2, 9, small);
    CHECK(std::vector<std::uint8_t>(again.begin(), again.end()) == std::vector<std::uint8_t>(once.begin(), once.end()));
}

TEST_CASE("snapshot_encoder builds once and patches each client's ack_sequence", "[protocol]") {
    const auto bodies = make_bodies(1000);
    ap::snapshot_encoder encoder;
    CHECK(encoder.frame().empty());
    encoder.build(77, bodies);

    std::vector<std::uint8_t> out;
    for (const std::uint32_t ack : {0u, 1u, 4242u, 0xffffffffu}) {
        encoder.copy_with_ack(ack, out);
        REQUIRE(out.size() == encoder.frame().size());
        const auto view = read_snapshot(out);
        CHECK(view.tick == 77);
        CHECK(view.ack_sequence == ack);
        REQUIRE(view.bodies.size() == bodies.size());
        CHECK(std::memcmp(view.bodies.data(), bodies.data(), bodies.size() * 32) == 0);
    }
    // The shared frame itself is untouched by the patches.
    const std::vector<std::uint8_t> shared(encoder.frame().begin(), encoder.frame().end());
    CHECK(read_snapshot(shared).ack_sequence == 0);

    // The next tick replaces the frame.
    encoder.build(78, std::span(bodies).first(2));
    const auto next_frame = encoder.frame_with_ack(5);
    const auto view = read_snapshot(next_frame);
    CHECK(view.tick == 78);
    CHECK(view.ack_sequence == 5);
    CHECK(view.bodies.size() == 2);
}
