// What the players hear of the game (server/match/game_feed.hpp): lines resent only when
// their standing changes, names once, events numbered once and dropped after the window.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

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
    CHECK(feed.collect(0, 0, out) == feed.version());
    REQUIRE(out.players.size() == 2);
    CHECK(out.name_ids == std::vector<uint32_t>{1, 2});
    CHECK(out.names == std::vector<std::string>{"ada", "bob"});
    const uint32_t after_first = feed.version();
    CHECK(after_first == 4);  // two lines, two names

    board[0].shots = 5;  // a shot alone: nothing new
    feed.update(2, board, {}, names);
    CHECK(feed.version() == after_first);
    feed.collect(after_first, 0, out);
    CHECK(out.empty());

    board[1].score = 20;  // a score: that line, with its shots as they are now
    board[1].shots = 9;
    feed.update(3, board, {}, names);
    feed.collect(after_first, 0, out);
    REQUIRE(out.players.size() == 1);
    CHECK(out.players[0].player == 2);
    CHECK(out.players[0].score == 20);
    CHECK(out.players[0].shots == 9);
    CHECK(out.name_ids.empty());
    // A client that holds nothing gets everything, with each line as it is now.
    feed.collect(0, 0, out);
    CHECK(out.players.size() == 2);
    CHECK(out.players[0].shots == 5);
}

TEST_CASE("events are numbered in order, sent after the held version and kept for the window", "[match][game]") {
    match::game_feed feed(10);
    const std::vector<rules::score_line> board{line(1, 0)};
    const std::vector<rules::game_event> a{{rules::event_kind::rock_hit, 3, 1, 0, 40, 20},
                                           {rules::event_kind::wave, 0, 0, 0, 0, 5}};
    feed.update(5, board, a, names);
    const uint32_t after_five = feed.version();
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
    feed.collect(after_five, 0, out);  // held what came with tick 5: only what came after
    REQUIRE(out.events.size() == 1);
    CHECK(out.events[0].sequence == 3);
    feed.collect(0, after_five, out);  // connected after tick 5: its lines, no event from before
    CHECK(out.events.size() == 1);
    CHECK(out.players.size() == 1);
    // Past the window the old events are gone.
    feed.update(16, board, {}, names);
    feed.collect(0, 0, out);
    REQUIRE(out.events.size() == 1);
    CHECK(out.events[0].sequence == 3);
    CHECK(feed.events_so_far() == 3);
}

TEST_CASE("within a byte limit the oldest changes go first, and the rest follow from where it stopped",
          "[match][game]") {
    // 32 players join, each named: their lines and names are far more than one datagram's
    // share; then events arrive.
    match::game_feed feed(600);
    std::map<world::player_id, std::string> many;
    std::vector<rules::score_line> board;
    for (uint32_t id = 1; id <= 32; ++id) {
        many[world::player_id{id}] = "pilot-number-" + std::to_string(id);
        board.push_back(line(id, 0));
        feed.update(id, board, {}, many);
    }
    const std::vector<rules::game_event> hit{{rules::event_kind::rock_hit, 3, 7, 0, 40, 20}};
    feed.update(40, board, hit, many);
    protocol::game_list all;
    feed.collect(0, 0, all);
    constexpr size_t limit = 300;
    REQUIRE(all.wire_bytes() > 4 * limit);

    // A client that acknowledges every snapshot: each part fits, they never repeat a line,
    // and together they are everything.
    uint32_t held = 0;
    protocol::game_list got, part;
    int parts = 0;
    while (held < feed.version()) {
        const uint32_t through = feed.collect(held, 0, part, limit);
        CHECK(part.wire_bytes() <= limit);
        REQUIRE(through > held);  // progress
        for (const auto& row : part.players) CHECK(std::ranges::count(got.players, row) == 0);
        got.players.insert(got.players.end(), part.players.begin(), part.players.end());
        got.name_ids.insert(got.name_ids.end(), part.name_ids.begin(), part.name_ids.end());
        got.names.insert(got.names.end(), part.names.begin(), part.names.end());
        got.events.insert(got.events.end(), part.events.begin(), part.events.end());
        held = through;
        ++parts;
    }
    CHECK(parts >= 4);
    std::ranges::sort(got.players, {}, &protocol::player_row::player);
    CHECK(got.players == all.players);
    CHECK(got.name_ids.size() == 32);
    REQUIRE(got.events.size() == 1);
    CHECK(got.events[0].sequence == 1);

    // A client whose acknowledgements are lost is sent the same first part again, not less.
    protocol::game_list again;
    const uint32_t first = feed.collect(0, 0, part, limit);
    CHECK(feed.collect(0, 0, again, limit) == first);
    CHECK(again == part);
    // Without a limit nothing is left out.
    CHECK(feed.collect(0, 0, again) == feed.version());
    CHECK(again == all);
}

TEST_CASE("a line that changes again while its older change waits goes once, as it is now", "[match][game]") {
    match::game_feed feed(96);
    std::vector<rules::score_line> board{line(1, 0), line(2, 0)};
    feed.update(1, board, {}, names);
    protocol::game_list out;
    // Room for one change at a time: line 1 first.
    const size_t one = protocol::game_list::line_bytes;
    uint32_t held = feed.collect(0, 0, out, one);
    REQUIRE(out.players.size() == 1);
    CHECK(out.players[0].player == 1);
    board[0].score = 50;  // line 1 changes again: it moves behind the others
    feed.update(2, board, {}, names);
    std::vector<uint32_t> order;
    while (held < feed.version()) {
        held = feed.collect(held, 0, out, one);
        for (const auto& row : out.players) order.push_back(row.player * 1000 + row.score);
    }
    CHECK(order == std::vector<uint32_t>{2000, 1050});
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

TEST_CASE("a game's declared values go one by one as they change, with its teams' and its events once",
          "[match][game][manifest]") {
    match::game_feed feed(96);
    feed.declare(2, 1);  // two player fields, one team field
    std::vector<rules::score_line> board{line(1, 0), line(2, 0)};
    board[0].values = {1, 0, 99};  // a third value the manifest does not declare: never sent
    board[1].values = {2, 0};
    std::vector<rules::team_line> teams{{1, "red", 0, {0}}, {2, "blue", 0, {0}}};
    feed.update(1, board, {}, names, teams);
    protocol::game_list out;
    feed.collect(0, 0, out);
    CHECK(out.player_values == std::vector<protocol::game_value>{{1, 0, 1}, {1, 1, 0}, {2, 0, 2}, {2, 1, 0}});
    CHECK(out.team_values == std::vector<protocol::game_value>{{1, 0, 0}, {2, 0, 0}});
    const uint32_t held = feed.version();

    // Player 2 scores: its goals and its team's, and the goal once, nothing else.
    board[1].values = {2, 1};
    teams[1].values = {1};
    const rules::declared_event goal{0, {2, 2}};
    feed.update(2, board, {}, names, teams, std::span(&goal, 1));
    feed.collect(held, held, out);
    CHECK(out.player_values == std::vector<protocol::game_value>{{2, 1, 1}});
    CHECK(out.team_values == std::vector<protocol::game_value>{{2, 0, 1}});
    REQUIRE(out.records.size() == 1);
    CHECK(out.records[0].sequence == 1);
    CHECK(out.records[0].tick == 2);
    CHECK(out.records[0].kind == 0);
    CHECK(out.records[0].values[0] == 2);
    CHECK(out.records[0].values[1] == 2);
    CHECK(out.wire_bytes() == 2 * protocol::game_list::value_bytes + protocol::game_list::record_bytes);
    feed.collect(feed.version(), feed.version(), out);
    CHECK(out.empty());

    // The final result holds every declared value.
    const protocol::match_result r = feed.result(0);
    CHECK(r.player_values == std::vector<protocol::game_value>{{1, 0, 1}, {1, 1, 0}, {2, 0, 2}, {2, 1, 1}});
    CHECK(r.team_values == std::vector<protocol::game_value>{{1, 0, 0}, {2, 0, 1}});
}
