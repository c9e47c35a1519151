#include "games/tag/tag_rules.hpp"

namespace arena::rules {

namespace {

constexpr uint8_t role_it = 1, role_runner = 2;  // "team" values: the manifest's teams
constexpr uint8_t kind_runner = 1, kind_it = 2;  // body tags: "it" changes hands, and so its tag
constexpr uint32_t tag_back_ticks = 60;          // one second at 60 Hz

}  // namespace

tag_rules::tag_rules(world::world& w) {
    w.set_contact_events(true);  // after_step reads who touched whom
}

void tag_rules::on_joins(world::world& w, std::span<const uint32_t> owners, std::span<const uint32_t> bodies) {
    for (size_t k = 0; k < owners.size() && k < bodies.size(); ++k) {
        if (bodies[k] == 0) continue;
        players_[owners[k]].body = bodies[k];
        if (it_ == 0) make_it(owners[k], w.tick());  // the first player is "it"
    }
}

void tag_rules::on_leaves(world::world& w, std::span<const uint32_t> bodies) {
    for (const uint32_t body : bodies)
        for (auto it = players_.begin(); it != players_.end(); ++it)
            if (it->second.body == body) {
                if (it_ == it->first) it_ = 0;
                players_.erase(it);
                break;
            }
    if (it_ == 0 && !players_.empty()) make_it(players_.begin()->first, w.tick());  // the lowest id
}

void tag_rules::after_step(world::world& w) {
    events_.clear();
    if (it_ == 0) return;
    players_[it_].ticks_it += 1;
    if (w.tick() < immune_until_) return;
    // Contact events come sorted by body ids: the same touch passes "it" the same way everywhere.
    const uint32_t it_body = players_[it_].body;
    for (const world::contact_event& e : w.contact_events()) {
        if (e.a != it_body && e.b != it_body) continue;
        const uint32_t other = e.a == it_body ? e.b : e.a;
        for (const auto& [id, p] : players_)
            if (p.body == other) {
                events_.push_back({0, {static_cast<int32_t>(it_), static_cast<int32_t>(id)}});
                make_it(id, w.tick());
                return;
            }
    }
}

void tag_rules::make_it(uint32_t player, uint32_t tick) {
    // Both bodies change their tag: the clients that hold them get them again (take_retagged).
    if (const auto old = players_.find(it_); old != players_.end()) retagged_.push_back(old->second.body);
    it_ = player;
    retagged_.push_back(players_[player].body);
    immune_until_ = tick + tag_back_ticks;
}

uint8_t tag_rules::kind_of(uint32_t body_id) const {
    for (const auto& [id, p] : players_)
        if (p.body == body_id) return id == it_ ? kind_it : kind_runner;
    return 0;
}

void tag_rules::take_retagged(std::vector<uint32_t>& into) {
    into.insert(into.end(), retagged_.begin(), retagged_.end());
    retagged_.clear();
}

void tag_rules::hash(world::fnv1a& h) const {
    h.add_u32(it_);
    h.add_u32(immune_until_);
    h.add_u32(static_cast<uint32_t>(players_.size()));
    for (const auto& [id, p] : players_) {
        h.add_u32(id);
        h.add_u32(p.body);
        h.add_u32(p.ticks_it);
    }
}

std::vector<score_line> tag_rules::scoreboard() const {
    std::vector<score_line> board;
    for (const auto& [id, p] : players_) {
        const int32_t role = id == it_ ? role_it : role_runner;
        board.push_back({.player = id, .values = {role, static_cast<int32_t>(p.ticks_it)}});
    }
    return board;
}

std::vector<uint32_t> tag_rules::winners() const {
    std::vector<uint32_t> least;  // every player tied at the least time as "it"
    for (const auto& [id, p] : players_) {
        if (!least.empty() && p.ticks_it > players_.at(least[0]).ticks_it) continue;
        if (!least.empty() && p.ticks_it < players_.at(least[0]).ticks_it) least.clear();
        least.push_back(id);
    }
    return least;
}

protocol::game_manifest tag_rules::manifest() const {
    using protocol::GameFieldKind;
    protocol::game_manifest m;
    m.name = "tag";
    m.player_fields = {{"role", "Role", GameFieldKind::team}, {"time_it", "Time it", GameFieldKind::ticks}};
    m.teams = {{"it", "#ff5040"}, {"runner", "#50a0ff"}};
    m.rank_field = "time_it";
    m.rank_ascending = true;  // the least time as "it" wins
    m.events = {{"tagged", {"player", "other_player"}, "{player} tagged {other_player}"}};
    m.body_tags = {{kind_runner, "runner", "ship", "#50a0ff"}, {kind_it, "it", "ship", "#ff5040"}};
    m.inputs = {{"dash", 0, "ShiftLeft"}};
    return m;
}

}  // namespace arena::rules
