// The game's fields on the wire (protocol/game.hpp): player lines, names and events in
// snapshots, and the final scoreboard in the Bye that ends a match, read back as written.
#include <catch2/catch.hpp>

#include <vector>

#include "protocol/decode.hpp"
#include "protocol/game.hpp"
#include "protocol/snapshot.hpp"
#include "protocol/verify.hpp"

namespace ap = arena::protocol;

namespace {

ap::game_list a_game() {
    ap::game_list g;
    g.players.push_back({1, 170, 0, 1, 12, 4, 2, ap::PlayerState::respawning});
    g.players.push_back({4, 0, 0, 4, 3, 0, 0, ap::PlayerState::out});
    g.name_ids = {1, 4};
    g.names = {"ada", "ünïcode"};
    g.events.push_back({8, 300, ap::GameEventKind::rock_hit, 2, 1, 0, 55, 50});
    g.events.push_back({9, 300, ap::GameEventKind::ship_destroyed, 0, 4, 1, 61, 0});
    g.events.push_back({10, 303, ap::GameEventKind::respawn, 0, 1, 0, 77, 0});
    g.events.push_back({11, 303, ap::GameEventKind::wave, 0, 0, 0, 0, 6});
    return g;
}

ap::snapshot_view read(std::span<const std::uint8_t> frame, std::vector<std::uint8_t>& storage) {
    storage.assign(frame.begin(), frame.end());
    const auto m = ap::verify_message(storage, ap::server_frame_limits);
    REQUIRE(m);
    const auto s = ap::decode_snapshot(*m.value);
    REQUIRE(s);
    return s.value;
}

}  // namespace

TEST_CASE("A snapshot's player lines, names and events read back as written", "[protocol][game]") {
    const ap::game_list game = a_game();
    const std::vector<ap::BodyState> bodies{{1, 1, 2, 3, 4, 5, 0.5f, 0}};
    flatbuffers::FlatBufferBuilder fbb;
    std::vector<std::uint8_t> storage;
    for (const bool delta : {false, true}) {
        const std::vector<std::uint8_t> codec{1, 2, 3};
        const auto frame = delta ? ap::encode_delta_snapshot(fbb, 9, 2, 6, codec, nullptr, &game)
                                 : ap::encode_snapshot(fbb, 9, 2, bodies, nullptr, &game);
        const ap::snapshot_view s = read(frame, storage);
        ap::game_list back;
        REQUIRE(ap::read_game(*s.table, back).empty());
        CHECK(back == game);
    }
    // The shared frame keeps them through the ack patch.
    ap::snapshot_encoder shared;
    shared.build(9, bodies, nullptr, &game);
    const ap::snapshot_view s = read(shared.frame_with_ack(77), storage);
    CHECK(s.ack_sequence == 77);
    ap::game_list back;
    REQUIRE(ap::read_game(*s.table, back).empty());
    CHECK(back == game);
}

TEST_CASE("A snapshot without the game's fields reads as no lines, names or events", "[protocol][game]") {
    flatbuffers::FlatBufferBuilder fbb;
    std::vector<std::uint8_t> storage;
    const ap::snapshot_view s = read(ap::encode_snapshot(fbb, 3, 1, {}), storage);
    ap::game_list back;
    REQUIRE(ap::read_game(*s.table, back).empty());
    CHECK(back.empty());
    // An empty list writes nothing: the frame is the one of before the game's fields.
    const ap::game_list none;
    const auto plain = ap::encode_snapshot(fbb, 3, 1, {});
    const std::vector<std::uint8_t> a(plain.begin(), plain.end());
    const auto with_none = ap::encode_snapshot(fbb, 3, 1, {}, nullptr, &none);
    CHECK(std::vector<std::uint8_t>(with_none.begin(), with_none.end()) == a);
}

TEST_CASE("Names that do not pair with their ids are refused with a reason", "[protocol][game]") {
    flatbuffers::FlatBufferBuilder fbb;
    fbb.ForceDefaults(false);
    const auto ids = fbb.CreateVector(std::vector<std::uint32_t>{1, 2});
    const auto names = fbb.CreateVectorOfStrings(std::vector<std::string>{"only one"});
    ap::finish_message(fbb, ap::Payload::Snapshot, ap::CreateSnapshot(fbb, 5, 0, 0, 0, 0, 0, 0, 0, ids, names).Union());
    std::vector<std::uint8_t> storage;
    const ap::snapshot_view s = read({fbb.GetBufferPointer(), fbb.GetSize()}, storage);
    ap::game_list back;
    CHECK(ap::read_game(*s.table, back) == "Snapshot: 2 player_name_ids for 1 player_names");
    CHECK(back.empty());
}

TEST_CASE("The Bye that ends a match carries the winner and the final scoreboard", "[protocol][game]") {
    ap::match_result r;
    r.over = true;
    r.winner = 1;
    r.scoreboard = a_game().players;
    r.names = a_game().names;
    std::vector<std::uint8_t> frame = ap::encode_bye("match over: score limit", &r);
    const auto m = ap::verify_message(frame, ap::server_frame_limits);
    REQUIRE(m);
    const auto bye = ap::decode_bye(*m.value);
    REQUIRE(bye);
    CHECK(bye.value.reason == "match over: score limit");
    CHECK(bye.value.result == r);

    // Any other Bye: no result, and the frame of before.
    const ap::match_result not_over;
    CHECK(ap::encode_bye("bye", &not_over) == ap::encode_bye("bye"));
    std::vector<std::uint8_t> plain = ap::encode_bye("bye");
    const auto pm = ap::verify_message(plain, ap::server_frame_limits);
    REQUIRE(pm);
    CHECK_FALSE(ap::decode_bye(*pm.value).value.result.over);
}
