#pragma once
// What the players hear of the game (protocol/README.md, "Players and game events"): each
// player's scoreboard line, each name, and the game's events of the last few snapshot
// intervals, numbered. The match updates it once per tick from the rules; each snapshot then
// carries what changed after what its client is known to hold (collect).
//
// Every change (a line's standing, a name appearing, an event) takes the next number of one
// count, its version, so that what a client holds is one number: every change up to it. A
// snapshot that must fit a datagram carries the oldest changes first, as many as fit, and
// says through which version it is complete: a list too long for one datagram (32 names on
// a client's first snapshot) goes over a few, and an acknowledgement never claims more than
// arrived.
#include <array>
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

    // How many values the game declares per player and per team (its manifest's fields): only
    // those go on the wire. None until called.
    void declare(size_t player_fields, size_t team_fields);

    // The state after the step that made world tick `tick`: the rules' scoreboard and events,
    // the players' names (by player id), the teams and the game's own events.
    void update(uint32_t tick, std::span<const rules::score_line> board, std::span<const rules::game_event> events,
                const std::map<world::player_id, std::string>& names, std::span<const rules::team_line> teams = {},
                std::span<const rules::declared_event> records = {});

    // Into `out` (cleared first): the lines and names whose version is after `after` (0:
    // every one), and the events after max(after, events_after), lines and names in player id
    // order. With `max_bytes` (game_list::wire_bytes; 0: no limit) only the oldest changes
    // that fit. Returns the version through which `out` completes what `after` held: version()
    // when nothing was left out.
    uint32_t collect(uint32_t after, uint32_t events_after, protocol::game_list& out, size_t max_bytes = 0);

    // The newest change's version (0: none yet).
    [[nodiscard]] uint32_t version() const { return version_; }

    // Every line now, in player id order, with its name and its declared values, and the
    // teams' values: the final scoreboard.
    [[nodiscard]] protocol::match_result result(uint32_t winner) const;

    [[nodiscard]] bool empty() const { return players_.empty(); }
    [[nodiscard]] uint32_t events_so_far() const { return next_sequence_ - 1; }

private:
    using values = std::array<int32_t, protocol::max_game_fields>;
    using versions = std::array<uint32_t, protocol::max_game_fields>;
    struct entry {
        protocol::player_row row;
        uint32_t changed = 0;  // version of the last change of score, kills, deaths, lives or state
        std::string name;
        uint32_t named = 0;  // version of its name's arrival; 0: not known yet
        values declared{};
        versions declared_changed{};  // each value's last change
    };
    struct team_entry {
        values declared{};
        versions declared_changed{};
    };
    struct versioned_event {
        uint32_t version;
        protocol::game_event event;
    };
    struct versioned_record {
        uint32_t version;
        protocol::event_record record;
    };
    // Takes `now` into `held`, each value that changed (or every one, `fresh`) under a new version.
    void take_values(const values& now, values& held, versions& changed, size_t count, bool fresh);
    // One of collect()'s candidates: its version and its bytes on the wire.
    struct change {
        uint32_t version;
        size_t bytes;
    };
    uint32_t keep_ticks_;
    std::map<uint32_t, entry> players_;  // by player id
    std::deque<versioned_event> events_;
    std::map<uint8_t, team_entry> teams_;  // by team number
    std::deque<versioned_record> records_;
    size_t player_fields_ = 0, team_fields_ = 0;
    uint32_t next_sequence_ = 1;
    uint32_t next_record_ = 1;
    uint32_t version_ = 0;
    std::vector<change> changes_;  // collect()'s scratch
};

}  // namespace arena::match
