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
        case rules::event_kind::shot_rewound:
            return protocol::GameEventKind::shot_rewound;
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

void game_feed::declare(size_t player_fields, size_t team_fields) {
    player_fields_ = std::min(player_fields, protocol::max_game_fields);
    team_fields_ = std::min(team_fields, protocol::max_game_fields);
}

void game_feed::take_values(const values& now, values& held, versions& changed, size_t count, bool fresh) {
    for (size_t f = 0; f < count; ++f) {
        if (!fresh && held[f] == now[f]) continue;
        held[f] = now[f];
        changed[f] = ++version_;
    }
}

void game_feed::update(uint32_t tick, std::span<const rules::score_line> board,
                       std::span<const rules::game_event> events, const std::map<world::player_id, std::string>& names,
                       std::span<const rules::team_line> teams, std::span<const rules::declared_event> records) {
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
        take_values(l.values, e.declared, e.declared_changed, player_fields_, added);
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
    for (const rules::team_line& t : teams) {
        auto [it, added] = teams_.try_emplace(t.team);
        take_values(t.values, it->second.declared, it->second.declared_changed, team_fields_, added);
    }
    for (const rules::declared_event& r : records) {
        protocol::event_record record{next_record_++, tick, r.kind, {}};
        std::copy(r.values.begin(), r.values.end(), record.values);
        records_.push_back({++version_, record});
    }
    while (!records_.empty() && records_.front().record.tick + keep_ticks_ < tick) records_.pop_front();
}

uint32_t game_feed::collect(uint32_t after, uint32_t events_after, protocol::game_list& out, size_t max_bytes) {
    out.clear();
    // Events are in version order: skip to the first one after both marks.
    const uint32_t from = std::max(after, events_after);
    const auto first_event = std::upper_bound(events_.begin(), events_.end(), from,
                                              [](uint32_t v, const versioned_event& e) { return v < e.version; });
    const auto first_record = std::upper_bound(records_.begin(), records_.end(), from,
                                               [](uint32_t v, const versioned_record& r) { return v < r.version; });
    // Through which version the changes fit, oldest first; the first always goes, so that a
    // client behind by more than a datagram still gets ahead.
    uint32_t through = version_;
    if (max_bytes != 0) {
        changes_.clear();
        for (const auto& [id, e] : players_) {
            if (e.changed > after) changes_.push_back({e.changed, protocol::game_list::line_bytes});
            if (e.named > after) changes_.push_back({e.named, protocol::game_list::name_bytes(e.name)});
            for (size_t f = 0; f < player_fields_; ++f)
                if (e.declared_changed[f] > after)
                    changes_.push_back({e.declared_changed[f], protocol::game_list::value_bytes});
        }
        for (const auto& [team, t] : teams_)
            for (size_t f = 0; f < team_fields_; ++f)
                if (t.declared_changed[f] > after)
                    changes_.push_back({t.declared_changed[f], protocol::game_list::value_bytes});
        for (auto it = first_event; it != events_.end(); ++it)
            changes_.push_back({it->version, protocol::game_list::event_bytes});
        for (auto it = first_record; it != records_.end(); ++it)
            changes_.push_back({it->version, protocol::game_list::record_bytes});
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
        for (size_t f = 0; f < player_fields_; ++f)
            if (e.declared_changed[f] > after && e.declared_changed[f] <= through)
                out.player_values.push_back({id, static_cast<uint8_t>(f), e.declared[f]});
    }
    for (const auto& [team, t] : teams_)
        for (size_t f = 0; f < team_fields_; ++f)
            if (t.declared_changed[f] > after && t.declared_changed[f] <= through)
                out.team_values.push_back({team, static_cast<uint8_t>(f), t.declared[f]});
    for (auto it = first_event; it != events_.end() && it->version <= through; ++it) out.events.push_back(it->event);
    for (auto it = first_record; it != records_.end() && it->version <= through; ++it)
        out.records.push_back(it->record);
    return through;
}

protocol::match_result game_feed::result(uint32_t winner) const {
    protocol::match_result r;
    r.over = true;
    r.winner = winner;
    for (const auto& [id, e] : players_) {
        r.scoreboard.push_back(e.row);
        r.names.push_back(e.name);
        for (size_t f = 0; f < player_fields_; ++f)
            r.player_values.push_back({id, static_cast<uint8_t>(f), e.declared[f]});
    }
    for (const auto& [team, t] : teams_)
        for (size_t f = 0; f < team_fields_; ++f)
            r.team_values.push_back({team, static_cast<uint8_t>(f), t.declared[f]});
    return r;
}

}  // namespace arena::match
