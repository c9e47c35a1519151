// Hostile bytes never crash the reader, the verifier or the decoders: every byte of a valid
// frame of each type is overwritten with a few values, and whatever verifies is decoded
// (under the sanitizer build this proves no out-of-bounds read). A poor man's fuzzer,
// deterministic so that it runs in every ctest.
#include <catch2/catch.hpp>

#include <vector>

#include "protocol/decode.hpp"
#include "protocol/messages.hpp"
#include "protocol/snapshot.hpp"
#include "protocol/verify.hpp"
#include "stream.hpp"

namespace ap = arena::protocol;

namespace {

// Reads everything a peer could make us read; returns a checksum so nothing is optimised out.
std::size_t touch_everything(const ap::Message& m) {
    std::size_t sum = 0;
    if (auto r = ap::decode_hello(m)) sum += r.value.name.size() + r.value.token.size();
    if (auto r = ap::decode_welcome(m)) sum += r.value.world_config.size() + r.value.preset.size();
    if (auto r = ap::decode_reject(m)) sum += r.value.reason.size();
    if (auto r = ap::decode_input(m)) sum += r.value.sequence;
    if (auto r = ap::decode_ping(m)) sum += r.value.client_time;
    if (auto r = ap::decode_pong(m)) sum += r.value.server_tick;
    if (auto r = ap::decode_bye(m)) sum += r.value.reason.size();
    if (auto r = ap::decode_snapshot(m)) {
        for (const auto& b : r.value.bodies) sum += b.id() + static_cast<std::size_t>(b.x() != 0);
    }
    return sum;
}

std::vector<std::vector<std::uint8_t>> sample_frames() {
    ap::welcome_info w{1, 2, 3, 60, 20, "preset", "{\"a\": 1}", 0x55, 1};
    std::vector<ap::BodyState> bodies(3, ap::BodyState(1, 2, 3.0f, 4.0f, 5.0f, 6.0f, 0.5f, 0.25f));
    flatbuffers::FlatBufferBuilder fbb;
    const auto snapshot = ap::encode_snapshot(fbb, 10, 11, bodies);
    return {
        ap::encode_hello(1, "name", "tok"),
        ap::encode_welcome(w),
        ap::encode_reject(ap::RejectCode::server_full, "full"),
        ap::encode_input({1, 0.5f, -0.5f, 1}),
        ap::encode_ping(7),
        ap::encode_pong(7, 8),
        ap::encode_bye("bye"),
        {snapshot.begin(), snapshot.end()},
    };
}

}  // namespace

TEST_CASE("Every single-byte corruption of every message is refused or read safely", "[protocol]") {
    std::size_t accepted = 0;
    std::size_t refused = 0;
    std::size_t checksum = 0;
    for (const auto& original : sample_frames()) {
        for (std::size_t at = 0; at < original.size(); ++at) {
            for (const std::uint8_t value : {0x00, 0x01, 0x7f, 0x80, 0xff}) {
                auto bytes = original;
                if (bytes[at] == value) continue;
                bytes[at] = value;
                // Through the reader first, as bytes from a socket would come.
                const auto out = arena::protocol::test::read_stream(bytes, 5);
                for (const auto& frame : out.frames) {
                    const auto verified = ap::verify_message(frame);
                    if (verified) {
                        ++accepted;
                        checksum += touch_everything(*verified.value);
                    } else {
                        ++refused;
                        REQUIRE_FALSE(verified.error.empty());
                    }
                }
                if (!out.error.empty()) ++refused;
            }
        }
    }
    // Both happen: corrupting a scalar still verifies, corrupting an offset does not.
    CHECK(accepted > 0);
    CHECK(refused > 0);
    CHECK(checksum != 0);
}
