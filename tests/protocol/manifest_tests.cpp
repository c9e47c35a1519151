// A game's manifest (protocol/manifest.hpp): through the Welcome and back, its bounds, a
// corrupt buffer refused, and a Welcome that carries one still two tables deep for a verifier of
// before (its nested buffer is bytes to it).
#include <catch2/catch.hpp>

#include "protocol/decode.hpp"
#include "protocol/framing.hpp"
#include "protocol/manifest.hpp"
#include "protocol/messages.hpp"
#include "protocol/verify.hpp"

using namespace arena::protocol;

namespace {

game_manifest soccer_like() {
    game_manifest m;
    m.name = "soccer";
    m.player_fields = {{"team", "Team", GameFieldKind::team}, {"goals", "Goals", GameFieldKind::count}};
    m.team_fields = {{"goals", "Goals", GameFieldKind::count}};
    m.teams = {{"red", "#e04848"}, {"blue", "#4878e0"}};
    m.rank_field = "goals";
    m.events = {{"goal", {"player", "team"}, "{player} scores for {team}"}, {"kickoff", {}, "kick-off"}};
    m.body_tags = {{4, "ball", "disc", "#ffffff"}};
    m.inputs = {{"kick", 1, "Space"}};
    return m;
}

welcome_info welcome_with(const game_manifest& m) {
    welcome_info w;
    w.player_id = 1;
    w.entity_id = 2;
    w.tick_rate = 60;
    w.snapshot_rate = 20;
    w.game = m;
    return w;
}

}  // namespace

TEST_CASE("a manifest goes through the Welcome and back, equal", "[protocol][manifest]") {
    const frame_bytes frame = encode_welcome(welcome_with(soccer_like()));
    const auto message = verify_message(frame, server_frame_limits);
    REQUIRE(message.ok());
    const auto welcome = decode_welcome(*message.value);
    REQUIRE(welcome.ok());
    CHECK(welcome.value.game == soccer_like());
    CHECK(welcome.value.game.player_field("goals") == 1);
    CHECK(welcome.value.game.player_field("kills") == -1);

    // No manifest: no field, and the Welcome's bytes are those of before.
    const frame_bytes plain = encode_welcome(welcome_with({}));
    const auto plain_welcome = decode_welcome(*verify_message(plain, server_frame_limits).value);
    REQUIRE(plain_welcome.ok());
    CHECK(plain_welcome.value.game.empty());
    CHECK(plain.size() < frame.size());
}

TEST_CASE("a Welcome with a manifest stays two tables deep for a client's verifier", "[protocol][manifest][compat]") {
    // The limits every client of before applies to the server's frames (verify.hpp).
    const frame_bytes frame = encode_welcome(welcome_with(soccer_like()));
    REQUIRE(verify_message(frame, {.max_body = max_server_frame_body, .max_depth = 4, .max_tables = 4}).ok());
}

TEST_CASE("a manifest breaking a bound is named by its field", "[protocol][manifest]") {
    CHECK(manifest_problem(soccer_like()).empty());
    game_manifest m = soccer_like();
    m.player_fields.resize(max_game_fields + 1, {"x", "X", GameFieldKind::count});
    CHECK(manifest_problem(m) == "player_fields: more than 8 fields");
    m = soccer_like();
    m.player_fields[1].name = "Goals!";
    CHECK(manifest_problem(m) == "player_fields[1].name: 1 to 32 of a-z, 0-9 and _");
    m = soccer_like();
    m.player_fields[1].name = "team";
    CHECK(manifest_problem(m) == "player_fields[1].name: 'team' twice");
    m = soccer_like();
    m.rank_field = "kills";
    CHECK(manifest_problem(m) == "rank_field: 'kills' is not a player field");
    m = soccer_like();
    m.events[0].values = {"a", "b", "c", "d", "e"};
    CHECK(manifest_problem(m) == "events[0].values: more than 4");
    m = soccer_like();
    m.inputs[0].button = 8;
    CHECK(manifest_problem(m) == "inputs[0].button: a bit from 0 to 7");
    m = soccer_like();
    m.teams[0].name = std::string(65, 'r');
    CHECK(manifest_problem(m) == "teams[0].name: longer than 64 bytes");
}

TEST_CASE("a corrupt or out-of-bounds manifest buffer is refused with its reason", "[protocol][manifest]") {
    std::vector<uint8_t> buffer = encode_manifest(soccer_like());
    REQUIRE(decode_manifest(buffer).ok());
    CHECK(decode_manifest(std::vector<uint8_t>{}).value.empty());
    std::vector<uint8_t> broken = buffer;
    broken[0] = 0xff;  // the root offset points outside the buffer
    broken[1] = 0xff;
    CHECK(decode_manifest(broken).error == "FlatBuffer verification failed");
    game_manifest wide = soccer_like();
    wide.inputs[0].button = 9;  // encodable, but out of the protocol's bounds
    CHECK(decode_manifest(encode_manifest(wide)).error == "inputs[0].button: a bit from 0 to 7");
}
