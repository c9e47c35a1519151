#pragma once
// The game on the wire (README.md, "Players and game events"): each player's scoreboard line
// and name, and the game's events, carried by Snapshot; the final scoreboard and the winner,
// carried by the Bye that ends a match. Plain values to encode and to read back. Like the
// shapes these are vectors of structs (and one of strings), never tables: a client's verifier
// limits stay what they were, and a client that predates them skips them unread.
#include <cstdint>
#include <string>
#include <vector>

#include "protocol/arena_generated.h"
#include "protocol/manifest.hpp"

namespace arena::protocol {

// One scoreboard line (PlayerLine) as plain values.
struct player_row {
    std::uint32_t player = 0;
    std::uint32_t score = 0;
    std::uint32_t kills = 0;
    std::uint32_t deaths = 0;
    std::uint32_t shots = 0;
    std::uint32_t hits = 0;
    std::uint8_t lives = 0;
    PlayerState state = PlayerState::playing;
    bool operator==(const player_row&) const = default;
};

// One GameEvent as plain values.
struct game_event {
    std::uint32_t sequence = 0;  // 1, 2, 3...: a client takes each once
    std::uint32_t tick = 0;
    GameEventKind kind = GameEventKind::rock_hit;
    std::uint8_t size = 0;
    std::uint32_t player = 0;
    std::uint32_t other = 0;
    std::uint32_t body = 0;
    std::uint32_t value = 0;
    bool operator==(const game_event&) const = default;
};

[[nodiscard]] PlayerLine to_wire(const player_row& r);
[[nodiscard]] player_row from_wire(const PlayerLine& l);
[[nodiscard]] GameEvent to_wire(const game_event& e);
[[nodiscard]] game_event from_wire(const GameEvent& e);

// What one snapshot carries of the game, ready to encode (and what read_game gives back).
struct game_list {
    std::vector<player_row> players;
    std::vector<std::uint32_t> name_ids;  // names[i] is the name of player name_ids[i]
    std::vector<std::string> names;
    std::vector<game_event> events;
    // The game's declared state (manifest.hpp): values by player and by team, and its events.
    std::vector<game_value> player_values;
    std::vector<game_value> team_values;
    std::vector<event_record> records;
    void clear() {
        players.clear();
        name_ids.clear();
        names.clear();
        events.clear();
        player_values.clear();
        team_values.clear();
        records.clear();
    }
    [[nodiscard]] bool empty() const {
        return players.empty() && name_ids.empty() && events.empty() && player_values.empty() && team_values.empty() &&
               records.empty();
    }
    // Bytes these add to a message, FlatBuffers framing aside (a name: its id, its length
    // word, its bytes and the terminator), and each item's share of them.
    [[nodiscard]] std::size_t wire_bytes() const;
    static const std::size_t line_bytes;
    static const std::size_t event_bytes;
    static const std::size_t value_bytes;   // a GameValue
    static const std::size_t record_bytes;  // a GameEventRecord
    static std::size_t name_bytes(const std::string& name) { return sizeof(std::uint32_t) + 4 + name.size() + 1; }
    bool operator==(const game_list&) const = default;
};

// The end of a match as the last Bye tells it.
struct match_result {
    bool over = false;         // false: a Bye for another reason, nothing below
    std::uint32_t winner = 0;  // 0 = nobody
    std::vector<player_row> scoreboard;
    std::vector<std::string> names;  // names[i] is scoreboard[i]'s player's
    // The game's declared values at the end (manifest.hpp), the winning team (0: none) and the
    // winning players (a team's, or all tied at the top; empty: nobody).
    std::vector<game_value> player_values;
    std::vector<game_value> team_values;
    std::uint8_t winning_team = 0;
    std::vector<std::uint32_t> winners;
    bool operator==(const match_result&) const = default;
};

// Appends the game's fields of `snapshot` to `out`. The reason when they do not hold together
// (as many names as name ids); `out` is then unchanged.
[[nodiscard]] std::string read_game(const Snapshot& snapshot, game_list& out);

}  // namespace arena::protocol
