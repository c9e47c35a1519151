#include "protocol/game.hpp"

namespace arena::protocol {

PlayerLine to_wire(const player_row& r) {
    return {r.player, r.score, r.kills, r.deaths, r.shots, r.hits, r.lives, r.state};
}

player_row from_wire(const PlayerLine& l) {
    return {l.player_id(), l.score(), l.kills(), l.deaths(), l.shots(), l.hits(), l.lives(), l.state()};
}

GameEvent to_wire(const game_event& e) {
    return {e.sequence, e.tick, e.kind, e.size, e.player, e.other, e.body, e.value};
}

game_event from_wire(const GameEvent& e) {
    return {e.sequence(), e.tick(), e.kind(), e.size(), e.player(), e.other(), e.body(), e.value()};
}

const std::size_t game_list::line_bytes = sizeof(PlayerLine);
const std::size_t game_list::event_bytes = sizeof(GameEvent);
const std::size_t game_list::value_bytes = sizeof(GameValue);
const std::size_t game_list::record_bytes = sizeof(GameEventRecord);

std::size_t game_list::wire_bytes() const {
    std::size_t bytes = players.size() * line_bytes + events.size() * event_bytes +
                        (player_values.size() + team_values.size()) * value_bytes + records.size() * record_bytes;
    for (const std::string& n : names) bytes += name_bytes(n);
    return bytes;
}

std::string read_game(const Snapshot& snapshot, game_list& out) {
    const auto* ids = snapshot.player_name_ids();
    const auto* names = snapshot.player_names();
    const std::size_t id_count = ids == nullptr ? 0 : ids->size();
    const std::size_t name_count = names == nullptr ? 0 : names->size();
    if (id_count != name_count)
        return "Snapshot: " + std::to_string(id_count) + " player_name_ids for " + std::to_string(name_count) +
               " player_names";
    if (const auto* players = snapshot.players())
        for (const PlayerLine* l : *players) out.players.push_back(from_wire(*l));
    for (std::size_t i = 0; i < id_count; ++i) {
        const auto k = static_cast<flatbuffers::uoffset_t>(i);
        out.name_ids.push_back(ids->Get(k));
        out.names.push_back(names->Get(k)->str());
    }
    if (const auto* events = snapshot.events())
        for (const GameEvent* e : *events) out.events.push_back(from_wire(*e));
    if (const auto* values = snapshot.player_values())
        for (const GameValue* v : *values) out.player_values.push_back(from_wire(*v));
    if (const auto* values = snapshot.team_values())
        for (const GameValue* v : *values) out.team_values.push_back(from_wire(*v));
    if (const auto* records = snapshot.game_events())
        for (const GameEventRecord* e : *records) out.records.push_back(from_wire(*e));
    return {};
}

}  // namespace arena::protocol
