// The pure half of high density on Agones: which request comes next for the Counter `rooms`
// and the List `players`, given what the process wants and what the sidecar confirmed; and
// the JSON of the sidecar's answers and of its GameServer watch.
#include <catch2/catch.hpp>

#include "server/ops/agones_json.hpp"
#include "server/ops/density_reconciler.hpp"

using namespace arena::ops;
using k = sidecar_call::kind;

namespace {

density_state state(int64_t rooms, std::set<std::string> players = {}) {
    return density_state{rooms, std::move(players)};
}

// Answers every call as a sidecar holding `count` and `values` would, until in sync; returns
// the calls made.
std::vector<sidecar_call> run_to_sync(density_reconciler& r, int64_t& count, std::set<std::string>& values) {
    std::vector<sidecar_call> made;
    while (auto call = r.next()) {
        REQUIRE(made.size() < 100);
        made.push_back(*call);
        switch (call->what) {
            case k::read_rooms:
                r.answered(*call, sidecar_outcome::done, count);
                break;
            case k::change_rooms:
                count += call->diff;
                r.answered(*call, sidecar_outcome::done);
                break;
            case k::read_players:
                r.answered(*call, sidecar_outcome::done, 0, {values.begin(), values.end()});
                break;
            case k::add_player:
                values.insert(call->value);
                r.answered(*call, sidecar_outcome::done);
                break;
            case k::remove_player:
                values.erase(call->value);
                r.answered(*call, sidecar_outcome::done);
                break;
        }
    }
    return made;
}

}  // namespace

TEST_CASE("density reconciler: reads first, then sends the one difference of rooms", "[ops][agones][density]") {
    density_reconciler r;
    r.want(state(3));
    auto call = r.next();
    REQUIRE(call);
    CHECK(call->what == k::read_rooms);
    r.answered(*call, sidecar_outcome::done, 1);
    call = r.next();
    REQUIRE(call);
    CHECK(call->what == k::change_rooms);
    CHECK(call->diff == 2);
    r.answered(*call, sidecar_outcome::done);
    CHECK(r.confirmed_rooms() == 3);
    // Then the List: read, nothing to add.
    call = r.next();
    REQUIRE(call);
    CHECK(call->what == k::read_players);
    r.answered(*call, sidecar_outcome::done, 0, {});
    CHECK(r.in_sync());
    // A match ends: one decrement.
    r.want(state(2));
    call = r.next();
    REQUIRE(call);
    CHECK(call->what == k::change_rooms);
    CHECK(call->diff == -1);
}

TEST_CASE("density reconciler: a failed change is asked again, unchanged", "[ops][agones][density]") {
    density_reconciler r;
    r.want(state(2));
    r.answered(*r.next(), sidecar_outcome::done, 0);
    const sidecar_call first = *r.next();
    r.answered(first, sidecar_outcome::failed);
    REQUIRE(r.next());
    CHECK(*r.next() == first);
    CHECK(r.confirmed_rooms() == 0);
}

TEST_CASE("density reconciler: players are removed before others are added, each once", "[ops][agones][density]") {
    density_reconciler r;
    int64_t count = 0;
    std::set<std::string> sidecar{"a/1", "a/2", "stale/1"};
    r.want(state(1, {"a/1", "a/2", "b/1"}));
    const auto calls = run_to_sync(r, count, sidecar);
    CHECK(count == 1);
    CHECK(sidecar == std::set<std::string>{"a/1", "a/2", "b/1"});
    std::vector<std::pair<k, std::string>> list_calls;
    for (const auto& c : calls)
        if (c.what == k::add_player || c.what == k::remove_player) list_calls.emplace_back(c.what, c.value);
    CHECK(list_calls == std::vector<std::pair<k, std::string>>{{k::remove_player, "stale/1"}, {k::add_player, "b/1"}});
}

TEST_CASE("density reconciler: an allocation's increment is read, not added to", "[ops][agones][density]") {
    density_reconciler r;
    int64_t count = 0;
    std::set<std::string> values;
    r.want(state(1));
    run_to_sync(r, count, values);
    REQUIRE(count == 1);
    // The allocator counts the match it allocates; the process creates it: 2 wanted, 2 held.
    count = 2;
    r.want(state(2));
    r.observed(2, true);
    const auto calls = run_to_sync(r, count, values);
    CHECK(count == 2);
    REQUIRE(calls.size() == 1);
    CHECK(calls[0].what == k::read_rooms);
}

TEST_CASE("density reconciler: a read sent before the GameServer moved does not count", "[ops][agones][density]") {
    density_reconciler r;
    r.want(state(2));
    const sidecar_call read = *r.next();
    REQUIRE(read.what == k::read_rooms);
    r.observed(2, true);  // the watch shows an allocation while the read is on its way
    r.answered(read, sidecar_outcome::done, 1);
    REQUIRE(r.next());
    CHECK(r.next()->what == k::read_rooms);  // read again, rather than sending +1 on a stale count
    CHECK_FALSE(r.confirmed_rooms());
}

TEST_CASE("density reconciler: a watch count equal to the confirmed one changes nothing", "[ops][agones][density]") {
    density_reconciler r;
    int64_t count = 0;
    std::set<std::string> values;
    r.want(state(3));
    run_to_sync(r, count, values);
    r.observed(3, true);  // the sidecar applied our own change
    CHECK(r.in_sync());
    CHECK(r.confirmed_rooms() == 3);
}

TEST_CASE("density reconciler: an unknown key is never asked about again", "[ops][agones][density]") {
    density_reconciler r;
    r.want(state(2, {"m/1"}));
    r.answered(*r.next(), sidecar_outcome::unknown_key);
    CHECK_FALSE(r.rooms_enabled());
    REQUIRE(r.next());
    CHECK(r.next()->what == k::read_players);
    r.answered(*r.next(), sidecar_outcome::unknown_key);
    CHECK_FALSE(r.players_enabled());
    CHECK(r.in_sync());
    r.want(state(5, {"x/1"}));
    CHECK_FALSE(r.next());

    density_reconciler undeclared;  // the GameServer's status names neither
    undeclared.want(state(2, {"m/1"}));
    undeclared.observed(std::nullopt, false);
    CHECK_FALSE(undeclared.next());
}

TEST_CASE("agones json: int64s are strings, zeros may be absent", "[ops][agones][density]") {
    CHECK(agones_json::count_diff_body(-2) == R"({"countDiff":"-2"})");
    CHECK(agones_json::list_value_body("m\"1/2") == R"({"value":"m\"1/2"})");
    CHECK(agones_json::counter_count(R"({"name":"rooms","count":"7","capacity":"10"})") == 7);
    CHECK(agones_json::counter_count(R"({"name":"rooms","capacity":"10"})") == 0);
    CHECK(agones_json::counter_count(R"({"count":7})") == 7);
    CHECK_FALSE(agones_json::counter_count(R"({"count":"seven"})"));
    CHECK_FALSE(agones_json::counter_count("not json"));
    CHECK(agones_json::list_values(R"({"name":"players","values":["a","b"]})") == std::vector<std::string>{"a", "b"});
    CHECK(agones_json::list_values(R"({"name":"players","capacity":"10"})") == std::vector<std::string>{});
    CHECK(agones_json::says_unknown_key(R"({"code":2,"message":"counter not found: rooms"})"));
    CHECK_FALSE(agones_json::says_unknown_key(R"({"message":"not found. Value: a not found in List: players"})"));
}

TEST_CASE("agones json: a watch line gives the allocation's annotations and the counter", "[ops][agones][density]") {
    const auto gs = agones_json::watch_event(
        R"({"result":{"object_meta":{"name":"gs-1","annotations":{"agones.dev/last-allocated":"2026-01-01T00:00:00Z",)"
        R"("arena.dev/mode":"duel","arena.dev/match":"finals"}},"status":{"state":"Allocated",)"
        R"("counters":{"rooms":{"count":"4","capacity":"50"}},"lists":{"players":{"capacity":"100"}}}}})");
    REQUIRE(gs);
    CHECK(gs->last_allocated == "2026-01-01T00:00:00Z");
    CHECK(gs->mode == "duel");
    CHECK(gs->match == "finals");
    CHECK(gs->rooms_count == 4);
    CHECK(gs->players_declared);

    const auto plain =
        agones_json::watch_event(R"({"result":{"metadata":{"name":"gs-1"},"status":{"state":"Ready"}}})");
    REQUIRE(plain);
    CHECK(plain->last_allocated.empty());
    CHECK_FALSE(plain->rooms_count);
    CHECK_FALSE(plain->players_declared);
    CHECK_FALSE(agones_json::watch_event(R"({"error":{"code":14,"message":"unavailable"}})"));
    CHECK_FALSE(agones_json::watch_event("{"));
}
