// verify_message: each refusal path, fed the bad bytes, with a specific reason.
#include <catch2/catch.hpp>

#include <cstring>
#include <string>
#include <vector>

#include "protocol/decode.hpp"
#include "protocol/messages.hpp"
#include "protocol/verify.hpp"
#include "protocol/version.hpp"
#include "server/world/little_endian.hpp"

namespace ap = arena::protocol;
using Catch::Contains;

namespace {

std::vector<std::uint8_t> to_vector(const flatbuffers::FlatBufferBuilder& fbb) {
    return {fbb.GetBufferPointer(), fbb.GetBufferPointer() + fbb.GetSize()};
}

// A Message with any payload type, including ones the schema does not allow.
std::vector<std::uint8_t> message_with(ap::Payload type, bool with_table,
                                       const char* identifier = ap::file_identifier) {
    flatbuffers::FlatBufferBuilder fbb;
    flatbuffers::Offset<void> payload = 0;
    if (with_table) payload = ap::CreatePing(fbb, 5).Union();
    fbb.FinishSizePrefixed(ap::CreateMessage(fbb, type, payload), identifier);
    return to_vector(fbb);
}

void set_le32(std::vector<std::uint8_t>& bytes, std::size_t at, std::uint32_t v) {
    arena::world::store_le32(bytes.data() + at, v);
}

// Writes the prefix that matches bytes' actual size, so only the body is at fault.
void fix_prefix(std::vector<std::uint8_t>& bytes) {
    set_le32(bytes, 0, static_cast<std::uint32_t>(bytes.size() - 4));
}

std::string refusal(const std::vector<std::uint8_t>& frame, const ap::verify_limits& limits = {}) {
    const auto r = ap::verify_message(frame, limits);
    REQUIRE_FALSE(r);
    CHECK(r.value == nullptr);
    CHECK_FALSE(r.error.empty());
    return r.error;
}

}  // namespace

TEST_CASE("A frame shorter than prefix and identifier is refused", "[protocol]") {
    CHECK_THAT(refusal({}), Contains("too short"));
    std::vector<std::uint8_t> tiny = {7, 0, 0, 0, 1, 2, 3, 4, 5, 6, 7};
    CHECK_THAT(refusal(tiny), Contains("too short"));
}

TEST_CASE("A prefix that disagrees with the frame size is refused", "[protocol]") {
    auto frame = ap::encode_ping(1);
    set_le32(frame, 0, static_cast<std::uint32_t>(frame.size()));  // one too many
    CHECK_THAT(refusal(frame), Contains("length prefix") && Contains("does not match"));
}

TEST_CASE("A body above the verify limit is refused", "[protocol]") {
    const auto frame = ap::encode_hello(1, std::string(70000, 'x'), "");
    CHECK_THAT(refusal(frame), Contains("frame length") && Contains("exceeds the limit of 65536"));
    CHECK(ap::verify_message(frame, ap::server_frame_limits));
}

TEST_CASE("Garbage without the file identifier is refused as not an Arena message", "[protocol]") {
    std::vector<std::uint8_t> garbage(64);
    std::uint32_t x = 12345;
    for (auto& b : garbage) b = static_cast<std::uint8_t>((x = x * 1103515245u + 12345u) >> 24);
    fix_prefix(garbage);
    CHECK_THAT(refusal(garbage), Contains("file identifier"));
}

TEST_CASE("Garbage behind a correct identifier fails verification", "[protocol]") {
    std::vector<std::uint8_t> garbage(64, 0xee);
    fix_prefix(garbage);
    std::memcpy(garbage.data() + 8, "ARNA", 4);
    CHECK_THAT(refusal(garbage), Contains("verification failed"));
}

TEST_CASE("A wrong file identifier is refused", "[protocol]") {
    CHECK_THAT(refusal(message_with(ap::Payload::Ping, true, "RPLY")), Contains("file identifier is not \"ARNA\""));
    // No identifier at all: bytes 4..7 of the body are then the vtable, not "ARNA".
    CHECK_THAT(refusal(message_with(ap::Payload::Ping, true, nullptr)), Contains("file identifier"));
}

TEST_CASE("Payload type NONE is refused", "[protocol]") {
    CHECK(refusal(message_with(ap::Payload::NONE, false)) == "unknown payload type 0 (NONE)");
}

TEST_CASE("A payload type outside the schema is refused", "[protocol]") {
    // The generated verifier accepts unknown union types (forward compatibility): we do not.
    CHECK(refusal(message_with(static_cast<ap::Payload>(9), true)) == "unknown payload type 9");
    CHECK(refusal(message_with(static_cast<ap::Payload>(200), true)) == "unknown payload type 200");
}

TEST_CASE("A payload type without its table is refused", "[protocol]") {
    CHECK(refusal(message_with(ap::Payload::Hello, false)) == "payload type Hello has no payload table");
}

TEST_CASE("A truncated buffer fails verification", "[protocol]") {
    const auto whole = ap::encode_hello(1, "a rather long player name", "token");
    // Every shorter cut, with a prefix made consistent so that only the body is at fault. A
    // cut through trailing alignment padding loses nothing and may verify: then it must read
    // exactly as the original.
    for (std::size_t size = 12; size < whole.size(); ++size) {
        std::vector<std::uint8_t> cut(whole.begin(), whole.begin() + size);
        fix_prefix(cut);
        INFO("size " << size);
        const auto r = ap::verify_message(cut);
        if (r) {
            CHECK(whole.size() - size < 8);
            CHECK(ap::decode_hello(*r.value).value == ap::hello_msg{1, "a rather long player name", "token"});
        }
    }
    std::vector<std::uint8_t> cut(whole.begin(), whole.end() - 8);
    fix_prefix(cut);
    CHECK_THAT(refusal(cut), Contains("verification failed"));
}

TEST_CASE("An out-of-range root offset fails verification", "[protocol]") {
    auto frame = ap::encode_ping(1);
    set_le32(frame, 4, 0x00fffff0u);  // body bytes 0..3: offset of the root table
    CHECK_THAT(refusal(frame), Contains("verification failed"));
}

TEST_CASE("An out-of-range string offset inside a table fails verification", "[protocol]") {
    auto frame = ap::encode_hello(1, "name", "token");
    const auto* hello = ap::verify_message(frame).value->payload_as_Hello();
    REQUIRE(hello != nullptr);
    // Tables are flatbuffers::Table underneath; find where the name's offset is stored.
    const auto* field = reinterpret_cast<const flatbuffers::Table*>(hello)->GetAddressOf(ap::Hello::VT_NAME);
    REQUIRE(field != nullptr);
    set_le32(frame, static_cast<std::size_t>(field - frame.data()), 0x7ffffff0u);
    CHECK_THAT(refusal(frame), Contains("verification failed"));
}

TEST_CASE("A string that claims more bytes than the frame holds fails verification", "[protocol]") {
    auto frame = ap::encode_bye("bye bye");
    const auto* reason = ap::verify_message(frame).value->payload_as_Bye()->reason();
    const auto at = static_cast<std::size_t>(reinterpret_cast<const std::uint8_t*>(reason) - frame.data());
    set_le32(frame, at, 1000);  // the string's length field
    CHECK_THAT(refusal(frame), Contains("verification failed"));
}

TEST_CASE("The table limit is applied", "[protocol]") {
    const auto frame = ap::encode_ping(1);
    CHECK(ap::verify_message(frame));
    CHECK_THAT(refusal(frame, {.max_tables = 1}), Contains("nesting limit"));
    CHECK_THAT(refusal(frame, {.max_depth = 1}), Contains("nesting limit"));
}

TEST_CASE("A misaligned buffer is refused instead of read", "[protocol]") {
    const auto frame = ap::encode_ping(1);
    std::vector<std::uint8_t> shifted(frame.size() + 1);
    std::memcpy(shifted.data() + 1, frame.data(), frame.size());
    const auto r = ap::verify_message(std::span(shifted).subspan(1));
    REQUIRE_FALSE(r);
    CHECK_THAT(r.error, Contains("aligned"));
}
