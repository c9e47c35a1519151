#pragma once
// What the players hear of the game (protocol/README.md, "Players and game events"): each
// player's scoreboard line with the tick it last changed, each name with the tick it first
// appeared, and the game's events of the last few snapshot intervals, numbered. The match
// updates it once per tick from the rules; each snapshot then carries what changed after the
// newest tick its client is known to hold (collect).
#include <cstdint>
#include <deque>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "protocol/game.hpp"
#include "server/rules/rules.hpp"
#include "server/world/ids.hpp"

namespace arena::match {

class game_feed {
public:
    // Events older than `keep_ticks` ticks are dropped (a client that acknowledged nothing for
    // that long misses them; its lines still bring every score).
    explicit game_feed(uint32_t keep_ticks) : keep_ticks_(keep_ticks) {}

    // The state after the step that made world tick `tick`: the rules' scoreboard and events,
    // and the players' names (by player id).
    void update(uint32_t tick, std::span<const rules::score_line> board, std::span<const rules::game_event> events,
                const std::map<world::player_id, std::string>& names);

    // Into `out` (cleared first): the lines and names that changed after tick `after` (0:
    // every one), and the events of the ticks after max(after, events_after).
    void collect(uint32_t after, uint32_t events_after, protocol::game_list& out) const;

    // Every line now, in player id order, with its name: the final scoreboard.
    [[nodiscard]] protocol::match_result result(uint32_t winner) const;

    [[nodiscard]] bool empty() const { return players_.empty(); }
    [[nodiscard]] uint32_t events_so_far() const { return next_sequence_ - 1; }

private:
    struct entry {
        protocol::player_row row;
        uint32_t changed_at = 0;  // tick of the last change of score, kills, deaths, lives or state
        std::string name;
        uint32_t named_at = 0;  // tick its name was first known
    };
    uint32_t keep_ticks_;
    std::map<uint32_t, entry> players_;  // by player id
    std::deque<protocol::game_event> events_;
    uint32_t next_sequence_ = 1;
};

}  // namespace arena::match
