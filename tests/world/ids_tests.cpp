// The strong ids of bodies and players: their own types over the same 32 bits, made only on
// purpose, ordered and hashed as their numbers.
#include <catch2/catch.hpp>
#include <map>
#include <type_traits>
#include <unordered_set>

#include "server/world/ids.hpp"
#include "server/world/presets.hpp"
#include "server/world/world.hpp"

using namespace arena::world;

// A number is not an id, a body is not a player, and neither costs more than the number.
static_assert(!std::is_convertible_v<uint32_t, body_id>);
static_assert(!std::is_convertible_v<body_id, uint32_t>);
static_assert(!std::is_convertible_v<player_id, body_id>);
static_assert(!std::is_constructible_v<body_id, player_id>);
static_assert(sizeof(body_id) == sizeof(uint32_t) && std::is_trivially_copyable_v<body_id>);

TEST_CASE("ids compare, order and hash as their numbers, and 0 is none", "[world][ids]") {
    CHECK(body_id{3} == body_id{3});
    CHECK(body_id{3} != body_id{4});
    CHECK(body_id{3} < body_id{4});
    CHECK_FALSE(body_id{});
    CHECK(body_id{}.value() == 0);
    CHECK(player_id{7});
    CHECK(std::hash<player_id>{}(player_id{7}) == std::hash<uint32_t>{}(7));
    const std::unordered_set<body_id> seen{body_id{1}, body_id{2}, body_id{1}};
    CHECK(seen.size() == 2);
    std::map<player_id, int> by_player{{player_id{9}, 0}, {player_id{2}, 1}};
    CHECK(by_player.begin()->first == player_id{2});
}

TEST_CASE("a spawned body's id is the body's number and its owner the player's", "[world][ids]") {
    world w(asteroids_preset(), 1);
    const std::optional<body_id> id = w.spawn_player(player_id{42});
    REQUIRE(id);
    const body* b = w.find(*id);
    REQUIRE(b);
    CHECK(b->id == id->value());
    CHECK(b->owner == 42u);
    CHECK(w.find(id->value()) == b);
    w.remove_bodies(std::vector<body_id>{*id});
    CHECK(w.find(*id) == nullptr);
}
