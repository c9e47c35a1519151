// The header-only primitives the world, the protocol and the replay share: FNV-1a (32 and
// 64 bit), little-endian loads and stores, splitmix64. Each against its published reference
// values, so that a client in another language can check its own against the same numbers.
#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

#include "server/world/fnv1a.hpp"
#include "server/world/little_endian.hpp"
#include "server/world/rng.hpp"
#include "server/world/splitmix64.hpp"

using namespace arena::world;

namespace {

template <class Hash>
constexpr auto hash_of(std::string_view text) {
    Hash h;
    h.add_bytes(text);
    return h.value();
}

}  // namespace

TEST_CASE("FNV-1a 64 and 32 give the published test vectors", "[world][primitives]") {
    CHECK(hash_of<fnv1a_64>("") == 0xcbf29ce484222325ULL);
    CHECK(hash_of<fnv1a_64>("a") == 0xaf63dc4c8601ec8cULL);
    CHECK(hash_of<fnv1a_64>("foobar") == 0x85944171f73967e8ULL);
    CHECK(hash_of<fnv1a_32>("") == 0x811c9dc5U);
    CHECK(hash_of<fnv1a_32>("a") == 0xe40c292cU);
    CHECK(hash_of<fnv1a_32>("foobar") == 0xbf9cf968U);
    static_assert(hash_of<fnv1a_64>("a") == 0xaf63dc4c8601ec8cULL, "usable at compile time");
}

TEST_CASE("FNV-1a takes integers and floats as their little-endian bytes", "[world][primitives]") {
    const std::vector<std::uint8_t> bytes{0x78, 0x56, 0x34, 0x12, 0xef, 0xcd, 0xab, 0x89, 0x67, 0x45, 0x23, 0x01};
    fnv1a_64 from_bytes;
    from_bytes.add_bytes(bytes);
    fnv1a_64 from_fields;
    from_fields.add_u32(0x12345678U);
    from_fields.add_u64(0x0123456789abcdefULL);
    CHECK(from_fields.value() == from_bytes.value());

    fnv1a_64 one, one_bits, minus_zero, zero;
    one.add_f32(1.0f);
    one_bits.add_u32(0x3f800000U);
    CHECK(one.value() == one_bits.value());
    minus_zero.add_f32(-0.0f);
    zero.add_f32(0.0f);
    CHECK(minus_zero.value() != zero.value());
}

TEST_CASE("little-endian loads, stores and appends", "[world][primitives]") {
    const std::uint8_t wire[4] = {0x04, 0x03, 0x02, 0x01};
    CHECK(load_le32(wire) == 0x01020304U);

    std::uint8_t stored[4] = {};
    store_le32(stored, 0xa1b2c3d4U);
    CHECK(stored[0] == 0xd4);
    CHECK(stored[1] == 0xc3);
    CHECK(stored[2] == 0xb2);
    CHECK(stored[3] == 0xa1);

    std::vector<std::uint8_t> out{0xff};
    append_le32(out, 0xdeadbeefU);
    REQUIRE(out.size() == 5);
    CHECK(load_le32(out.data() + 1) == 0xdeadbeefU);
    CHECK(out[0] == 0xff);
}

TEST_CASE("splitmix64 gives the reference sequence, and the world's rng draws from it", "[world][primitives]") {
    splitmix64 s(0);
    CHECK(s.next() == 0xe220a8397b1dcdafULL);
    CHECK(s.next() == 0x6e789e6aa1b965f4ULL);
    CHECK(s.next() == 0x06c45d188009454fULL);
    CHECK(s.state() == 3 * splitmix64::gamma);

    splitmix64 plain(20240501);
    rng world_rng(20240501);
    for (int i = 0; i < 100; ++i) REQUIRE(world_rng.next_u64() == plain.next());
    CHECK(world_rng.state() == plain.state());
}
