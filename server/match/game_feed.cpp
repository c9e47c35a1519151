#include "server/match/game_feed.hpp"

#include <algorithm>

namespace arena::match {

namespace {

protocol::PlayerState wire_state(rules::player_state s) {
    switch (s) {
        case rules::player_state::respawning:
            return protocol::PlayerState::respawning;
        case rules::player_state::out:
            return protocol::PlayerState::out;
        case rules::player_state::playing:
            break;
    }
    return protocol::PlayerState::playing;
}

protocol::GameEventKind wire_kind(rules::event_kind k) {
    switch (k) {
        case rules::event_kind::ship_destroyed:
            return protocol::GameEventKind::ship_destroyed;
        case rules::event_kind::respawn:
            return protocol::GameEventKind::respawn;
        case rules::event_kind::wave:
            return protocol::GameEventKind::wave;
        case rules::event_kind::rock_hit:
            break;
    }
    return protocol::GameEventKind::rock_hit;
}

// The fields whose change sends a line again; shots and hits ride along.
bool same_standing(const protocol::player_row& a, const protocol::player_row& b) {
    return a.score == b.score && a.kills == b.kills && a.deaths == b.deaths && a.lives == b.lives && a.state == b.state;
}

}  // namespace

void game_feed::update(uint32_t tick, std::span<const rules::score_line> board,
                       std::span<const rules::game_event> events,
                       const std::map<world::player_id, std::string>& names) {
    for (const rules::score_line& l : board) {
        const protocol::player_row row{l.player,
                                       l.score,
                                       l.kills,
                                       l.deaths,
                                       l.shots,
                                       l.hits,
                                       static_cast<uint8_t>(std::min<uint32_t>(l.lives, 255)),
                                       wire_state(l.state)};
        auto [it, added] = players_.try_emplace(l.player);
        entry& e = it->second;
        if (added || !same_standing(e.row, row)) e.changed_at = tick;
        e.row = row;
        if (e.named_at == 0) {
            if (const auto n = names.find(world::player_id{l.player}); n != names.end()) {
                e.name = n->second;
                e.named_at = tick;
            }
        }
    }
    for (const rules::game_event& g : events)
        events_.push_back({next_sequence_++, tick, wire_kind(g.kind), g.size, g.player, g.other, g.body, g.value});
    while (!events_.empty() && events_.front().tick + keep_ticks_ < tick) events_.pop_front();
}

void game_feed::collect(uint32_t after, uint32_t events_after, protocol::game_list& out) const {
    out.clear();
    for (const auto& [id, e] : players_) {
        if (e.changed_at > after) out.players.push_back(e.row);
        if (e.named_at > after) {
            out.name_ids.push_back(id);
            out.names.push_back(e.name);
        }
    }
    const uint32_t from = std::max(after, events_after);
    // Events are in tick order: skip to the first one after `from`.
    auto it = std::upper_bound(events_.begin(), events_.end(), from,
                               [](uint32_t t, const protocol::game_event& e) { return t < e.tick; });
    out.events.assign(it, events_.end());
}

protocol::match_result game_feed::result(uint32_t winner) const {
    protocol::match_result r;
    r.over = true;
    r.winner = winner;
    for (const auto& [id, e] : players_) {
        r.scoreboard.push_back(e.row);
        r.names.push_back(e.name);
    }
    return r;
}

}  // namespace arena::match
