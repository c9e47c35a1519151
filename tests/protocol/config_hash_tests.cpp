#include <catch2/catch.hpp>

#include "protocol/config_hash.hpp"

namespace ap = arena::protocol;

TEST_CASE("world_config_hash is FNV-1a 64 (published test vectors)", "[protocol]") {
    CHECK(ap::world_config_hash("") == 0xcbf29ce484222325ull);
    CHECK(ap::world_config_hash("a") == 0xaf63dc4c8601ec8cull);
    CHECK(ap::world_config_hash("foobar") == 0x85944171f73967e8ull);
}

TEST_CASE("world_config_hash hashes bytes: one changed character changes it", "[protocol]") {
    CHECK(ap::world_config_hash("{\"gravity\": -9.81}") != ap::world_config_hash("{\"gravity\": -9.80}"));
    CHECK(ap::world_config_hash("\xff\x80") != ap::world_config_hash("\x7f\x80"));
}
