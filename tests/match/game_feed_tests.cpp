// What the players hear of the game (server/match/game_feed.hpp): lines resent only when
// their standing changes, names once, events numbered once and dropped after the window.
#include <catch2/catch.hpp>

#include "server/match/game_feed.hpp"

using namespace arena;

namespace {

rules::score_line line(uint32_t player, uint32_t score, uint32_t shots = 0) {
    rules::score_line l;
    l.player = player;
    l.score = score;
    l.shots = shots;
    l.lives = 3;
    return l;
}

const std::map<world::player_id, std::string> names{{world::player_id{1}, "ada"}, {world::player_id{2}, "bob"}};

}  // namespace

TEST_CASE("a line is sent when its standing changes, and shots ride along", "[match][game]") {
    match::game_feed feed(96);
    std::vector<rules::score_line> board{line(1, 0), line(2, 0)};
    feed.update(1, board, {}, names);
    protocol::game_list out;
    feed.collect(0, 0, out);
    REQUIRE(out.players.size() == 2);
    CHECK(out.name_ids == std::vector<uint32_t>{1, 2});
    CHECK(out.names == std::vector<std::string>{"ada", "bob"});

    board[0].shots = 5;  // a shot alone: nothing to send after tick 1
    feed.update(2, board, {}, names);
    feed.collect(1, 0, out);
    CHECK(out.empty());

    board[1].score = 20;  // a score: that line, with its shots as they are now
    board[1].shots = 9;
    feed.update(3, board, {}, names);
    feed.collect(2, 0, out);
    REQUIRE(out.players.size() == 1);
    CHECK(out.players[0].player == 2);
    CHECK(out.players[0].score == 20);
    CHECK(out.players[0].shots == 9);
    CHECK(out.name_ids.empty());
    // A client that holds tick 1 gets the same; one that holds nothing gets everything.
    feed.collect(1, 0, out);
    CHECK(out.players.size() == 1);
    feed.collect(0, 0, out);
    CHECK(out.players.size() == 2);
    CHECK(out.players[0].shots == 5);
}

TEST_CASE("events are numbered in order, sent after the held tick and kept for the window", "[match][game]") {
    match::game_feed feed(10);
    const std::vector<rules::score_line> board{line(1, 0)};
    const std::vector<rules::game_event> a{{rules::event_kind::rock_hit, 3, 1, 0, 40, 20},
                                           {rules::event_kind::wave, 0, 0, 0, 0, 5}};
    feed.update(5, board, a, names);
    const std::vector<rules::game_event> b{{rules::event_kind::ship_destroyed, 0, 1, 0, 41, 0}};
    feed.update(8, board, b, names);
    protocol::game_list out;
    feed.collect(0, 0, out);
    REQUIRE(out.events.size() == 3);
    CHECK(out.events[0].sequence == 1);
    CHECK(out.events[0].tick == 5);
    CHECK(out.events[0].kind == protocol::GameEventKind::rock_hit);
    CHECK(out.events[0].size == 3);
    CHECK(out.events[0].body == 40);
    CHECK(out.events[0].value == 20);
    CHECK(out.events[1].kind == protocol::GameEventKind::wave);
    CHECK(out.events[2].sequence == 3);
    CHECK(out.events[2].kind == protocol::GameEventKind::ship_destroyed);
    feed.collect(5, 0, out);  // held tick 5: only what came after
    REQUIRE(out.events.size() == 1);
    CHECK(out.events[0].sequence == 3);
    feed.collect(0, 6, out);  // joined at tick 6: nothing from before
    CHECK(out.events.size() == 1);
    // Past the window the old events are gone.
    feed.update(16, board, {}, names);
    feed.collect(0, 0, out);
    REQUIRE(out.events.size() == 1);
    CHECK(out.events[0].sequence == 3);
    CHECK(feed.events_so_far() == 3);
}

TEST_CASE("the result holds every line with its name and the rules' winner", "[match][game]") {
    match::game_feed feed(96);
    std::vector<rules::score_line> board{line(1, 120, 7), line(2, 40)};
    board[1].state = rules::player_state::out;
    board[1].lives = 0;
    feed.update(3, board, {}, names);
    const protocol::match_result r = feed.result(1);
    CHECK(r.over);
    CHECK(r.winner == 1);
    REQUIRE(r.scoreboard.size() == 2);
    CHECK(r.names == std::vector<std::string>{"ada", "bob"});
    CHECK(r.scoreboard[0].shots == 7);
    CHECK(r.scoreboard[1].state == protocol::PlayerState::out);
    CHECK(r.scoreboard[1].lives == 0);
}
