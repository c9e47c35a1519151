// The one rule for player names (protocol/player_name.hpp), shared by the server and
// arena-token.
#include <catch2/catch.hpp>
#include <string>

#include "protocol/player_name.hpp"

using arena::protocol::max_player_name_bytes;
using arena::protocol::player_name_problem;
using namespace std::string_literals;

TEST_CASE("player names: printable UTF-8 up to the limit is accepted", "[protocol][name]") {
    CHECK_FALSE(player_name_problem("ada.lovelace"));
    CHECK_FALSE(player_name_problem(""));
    CHECK_FALSE(player_name_problem("Zoë Ünal"));                  // two-byte sequences
    CHECK_FALSE(player_name_problem("\xe6\x97\xa5\xe6\x9c\xac"));  // 日本: three bytes each
    CHECK_FALSE(player_name_problem("\xf0\x9f\x9a\x80 rocket"));   // U+1F680: four bytes
    CHECK_FALSE(player_name_problem("\xf4\x8f\xbf\xbf"));          // U+10FFFF, the last code point
    CHECK_FALSE(player_name_problem(std::string(max_player_name_bytes, 'x')));
}

TEST_CASE("player names: too long, control characters and invalid UTF-8 are refused where they are",
          "[protocol][name]") {
    CHECK(*player_name_problem(std::string(max_player_name_bytes + 1, 'x')) == "name longer than 64 bytes");
    CHECK(*player_name_problem("eve\nINFO join player=1") == "name has a control character at byte 3 (0x0a)");
    CHECK(*player_name_problem("ad\0min"s) == "name has a control character at byte 2 (0x00)");
    CHECK(player_name_problem("tab\there"));
    CHECK(player_name_problem("esc\x1b[31m"));
    CHECK(*player_name_problem("del\x7f") == "name has a control character at byte 3 (0x7f)");
    CHECK(*player_name_problem("c1\xc2\x85") == "name has a control character at byte 2 (0xc2)");  // U+0085 NEL
    CHECK(*player_name_problem("bad\xff") == "name is not valid UTF-8 at byte 3 (0xff)");
    CHECK(player_name_problem("\x80"));              // a continuation byte alone
    CHECK(player_name_problem("\xc3"));              // a sequence cut short
    CHECK(player_name_problem("\xc0\xaf"));          // overlong '/'
    CHECK(player_name_problem("\xe0\x80\xaf"));      // overlong, three bytes
    CHECK(player_name_problem("\xed\xa0\x80"));      // a UTF-16 surrogate (U+D800)
    CHECK(player_name_problem("\xf4\x90\x80\x80"));  // past U+10FFFF
    CHECK(
        player_name_problem("\xe6\x97"
                            "a"));        // a continuation replaced by ASCII
    CHECK(player_name_problem("ok", 1));  // a server with a lower limit
}
