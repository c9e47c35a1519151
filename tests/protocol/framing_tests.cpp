// frame_reader: length checks happen on the 4 prefix bytes, before any body byte is kept.
#include <catch2/catch.hpp>

#include <algorithm>
#include <vector>

#include "protocol/framing.hpp"
#include "protocol/messages.hpp"
#include "stream.hpp"

namespace ap = arena::protocol;
using arena::protocol::test::read_stream;

namespace {

std::vector<std::uint8_t> prefix(std::uint32_t length) {
    return {static_cast<std::uint8_t>(length), static_cast<std::uint8_t>(length >> 8),
            static_cast<std::uint8_t>(length >> 16), static_cast<std::uint8_t>(length >> 24)};
}

// A prefix followed by body_bytes bytes of filler, as a hostile peer would send them.
std::vector<std::uint8_t> prefix_then_body(std::uint32_t length, std::size_t body_bytes) {
    // Sized once: growing the 4-byte prefix vector trips g++ 12's -Warray-bounds at -O2.
    std::vector<std::uint8_t> bytes(4 + body_bytes, 0xab);
    const auto p = prefix(length);
    std::copy(p.begin(), p.end(), bytes.begin());
    return bytes;
}

}  // namespace

TEST_CASE("A length above 64 KiB is refused right after the prefix, nothing of the body kept", "[protocol]") {
    ap::frame_reader reader;  // client frames: 64 KiB
    const auto bytes = prefix_then_body(64 * 1024 + 1, 1000);
    const std::size_t consumed = reader.feed(bytes);
    CHECK(consumed == 4);
    REQUIRE(reader.failed());
    CHECK(reader.buffered() == 4);
    CHECK(reader.next_buffer().empty());
    CHECK(reader.frame().empty());
    CHECK(reader.error() == "frame length 65537 exceeds the limit of 65536 bytes");
    CHECK(reader.failure_kind() == ap::frame_reader::failure::too_large);
    // A failed stream stays failed: the connection must end.
    CHECK(reader.feed(bytes) == 0);
    reader.next();
    CHECK(reader.failed());
}

TEST_CASE("The largest length, 0xFFFFFFFF, is refused without allocating", "[protocol]") {
    const auto out = read_stream(prefix_then_body(0xffffffffu, 16), 1);
    CHECK(out.consumed == 4);
    CHECK(out.buffered == 4);
    CHECK_THAT(out.error, Catch::Contains("length 4294967295") && Catch::Contains("exceeds"));
}

TEST_CASE("A length of exactly the limit is accepted", "[protocol]") {
    ap::frame_reader reader(1024);
    const auto bytes = prefix_then_body(1024, 1024);
    CHECK(reader.feed(bytes) == bytes.size());
    REQUIRE(reader.has_frame());
    CHECK(reader.failure_kind() == ap::frame_reader::failure::none);
    CHECK(reader.body().size() == 1024);
    CHECK(reader.frame().size() == 1028);
}

TEST_CASE("A configurable limit: the server's larger frames pass a client-side reader", "[protocol]") {
    const auto bytes = prefix_then_body(1 << 20, 1 << 20);
    CHECK_FALSE(read_stream(bytes, bytes.size()).error.empty());
    const auto out = read_stream(bytes, bytes.size(), ap::max_server_frame_body);
    CHECK(out.error.empty());
    CHECK(out.frames.size() == 1);
}

TEST_CASE("A zero length is refused", "[protocol]") {
    const auto out = read_stream(prefix_then_body(0, 8), 1);
    CHECK(out.consumed == 4);
    CHECK(out.error == "frame length 0 is below the minimum of 8 bytes");
    ap::frame_reader reader;
    reader.feed(prefix_then_body(0, 8));
    CHECK(reader.failure_kind() == ap::frame_reader::failure::too_small);
}

TEST_CASE("A length too small to hold a FlatBuffer is refused", "[protocol]") {
    const auto out = read_stream(prefix_then_body(7, 7), 64);
    CHECK(out.consumed == 4);
    CHECK_THAT(out.error, Catch::Contains("frame length 7 is below the minimum"));
}

TEST_CASE("A truncated stream yields no frame and keeps the partial bytes", "[protocol]") {
    auto frame = ap::encode_hello(1, "name", "token");
    frame.pop_back();
    const auto out = read_stream(frame, 3);
    CHECK(out.error.empty());
    CHECK(out.frames.empty());
    CHECK(out.buffered == frame.size());
}

TEST_CASE("The exact-count interface asks for the prefix, then exactly the body", "[protocol]") {
    const auto frame = ap::encode_ping(1234);
    ap::frame_reader reader;
    REQUIRE(reader.current() == ap::frame_reader::state::need_prefix);
    auto want = reader.next_buffer();
    REQUIRE(want.size() == 4);
    std::copy_n(frame.begin(), 4, want.begin());
    reader.commit(4);

    REQUIRE(reader.current() == ap::frame_reader::state::need_body);
    want = reader.next_buffer();
    REQUIRE(want.size() == frame.size() - 4);
    // An async read may deliver less than asked: commit what came, then ask again.
    std::copy_n(frame.begin() + 4, 5, want.begin());
    reader.commit(5);
    want = reader.next_buffer();
    REQUIRE(want.size() == frame.size() - 9);
    std::copy(frame.begin() + 9, frame.end(), want.begin());
    reader.commit(want.size());

    REQUIRE(reader.has_frame());
    CHECK(std::vector<std::uint8_t>(reader.frame().begin(), reader.frame().end()) == frame);
    CHECK(reader.body().size() == frame.size() - 4);
    CHECK(reinterpret_cast<std::uintptr_t>(reader.frame().data()) % 8 == 0);
    CHECK(reader.next_buffer().empty());
    CHECK(reader.feed(frame) == 0);  // nothing taken until the ready frame is released

    reader.next();
    CHECK(reader.buffered() == 0);
    CHECK(reader.next_buffer().size() == 4);
    CHECK(reader.frame().empty());
}

TEST_CASE("The exact-count interface refuses an oversize prefix before asking for a body", "[protocol]") {
    ap::frame_reader reader(100);
    const auto bytes = prefix(101);
    auto want = reader.next_buffer();
    std::copy(bytes.begin(), bytes.end(), want.begin());
    reader.commit(4);
    CHECK(reader.failed());
    CHECK(reader.next_buffer().empty());  // the session never reads a body byte
    CHECK_THAT(std::string(reader.error()), Catch::Contains("exceeds the limit of 100"));
}

TEST_CASE("A whole aligned frame is handed over where it lies, and anything else goes through feed()", "[protocol]") {
    const auto ping = ap::encode_ping(1234);
    const auto second = ap::encode_ping(5678);
    // Two frames back to back in an 8-byte aligned buffer, and one byte more.
    std::vector<std::uint64_t> words((ping.size() + second.size() + 1 + 7) / 8);
    auto* base = reinterpret_cast<std::uint8_t*>(words.data());
    std::copy(ping.begin(), ping.end(), base);
    std::copy(second.begin(), second.end(), base + ping.size());
    const std::span<const std::uint8_t> all(base, ping.size() + second.size() + 1);

    ap::frame_reader reader;
    const auto whole = reader.whole_frame_at(all);
    REQUIRE(whole.data() == base);  // in place, not a copy
    CHECK(std::vector<std::uint8_t>(whole.begin(), whole.end()) == std::vector<std::uint8_t>(ping.begin(), ping.end()));

    // Not on an 8-byte boundary: FlatBuffers reads in place, so the reader must copy it.
    CHECK(reader.whole_frame_at(all.subspan(1)).empty());
    // Cut short: the rest is on its way.
    CHECK(reader.whole_frame_at(all.first(ping.size() - 1)).empty());
    CHECK(reader.whole_frame_at(all.first(3)).empty());
    // A reader holding part of a frame takes nothing in place: its bytes come first.
    CHECK(reader.feed(all.first(2)) == 2);
    CHECK(reader.whole_frame_at(all).empty());

    // Out of bounds lengths are left to feed(), which refuses them as it always does.
    ap::frame_reader small(100);
    const auto too_large = prefix_then_body(101, 101);
    std::vector<std::uint64_t> large_words((too_large.size() + 7) / 8);
    auto* large = reinterpret_cast<std::uint8_t*>(large_words.data());
    std::copy(too_large.begin(), too_large.end(), large);
    CHECK(small.whole_frame_at({large, too_large.size()}).empty());
    std::copy_n(prefix(0).begin(), 4, large);
    CHECK(small.whole_frame_at({large, too_large.size()}).empty());
}
