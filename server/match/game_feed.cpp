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
        if (added || !same_standing(e.row, row)) e.changed = ++version_;
        e.row = row;
        if (e.named == 0) {
            if (const auto n = names.find(world::player_id{l.player}); n != names.end()) {
                e.name = n->second;
                e.named = ++version_;
            }
        }
    }
    for (const rules::game_event& g : events)
        events_.push_back(
            {++version_, {next_sequence_++, tick, wire_kind(g.kind), g.size, g.player, g.other, g.body, g.value}});
    while (!events_.empty() && events_.front().event.tick + keep_ticks_ < tick) events_.pop_front();
}

uint32_t game_feed::collect(uint32_t after, uint32_t events_after, protocol::game_list& out, size_t max_bytes) {
    out.clear();
    // Events are in version order: skip to the first one after both marks.
    const uint32_t from = std::max(after, events_after);
    const auto first_event = std::upper_bound(events_.begin(), events_.end(), from,
                                              [](uint32_t v, const versioned_event& e) { return v < e.version; });
    // Through which version the changes fit, oldest first; the first always goes, so that a
    // client behind by more than a datagram still gets ahead.
    uint32_t through = version_;
    if (max_bytes != 0) {
        changes_.clear();
        for (const auto& [id, e] : players_) {
            if (e.changed > after) changes_.push_back({e.changed, protocol::game_list::line_bytes});
            if (e.named > after) changes_.push_back({e.named, protocol::game_list::name_bytes(e.name)});
        }
        for (auto it = first_event; it != events_.end(); ++it)
            changes_.push_back({it->version, protocol::game_list::event_bytes});
        // Versions are unique: one order. (std::sort: the WebAssembly build's library has no
        // std::ranges::sort.)
        std::sort(changes_.begin(), changes_.end(),
                  [](const change& x, const change& y) { return x.version < y.version; });
        size_t bytes = 0;
        for (size_t k = 0; k < changes_.size(); ++k) {
            bytes += changes_[k].bytes;
            if (k > 0 && bytes > max_bytes) {
                through = changes_[k].version - 1;
                break;
            }
        }
    }
    for (const auto& [id, e] : players_) {
        if (e.changed > after && e.changed <= through) out.players.push_back(e.row);
        if (e.named > after && e.named <= through) {
            out.name_ids.push_back(id);
            out.names.push_back(e.name);
        }
    }
    for (auto it = first_event; it != events_.end() && it->version <= through; ++it) out.events.push_back(it->event);
    return through;
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
