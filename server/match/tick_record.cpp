#include "server/match/tick_record.hpp"

namespace arena::match {

std::vector<world::body_id> apply_tick(world::world& w, const tick_record& record) {
    // In one batch: spawn_player one join at a time scans every body per try (quadratic).
    std::vector<world::body_id> spawned = w.spawn_players(record.joins);
    w.remove_bodies(record.leaves);
    w.step(record.inputs);
    return spawned;
}

namespace {

// The rules take the ids' numbers (server/rules/rules.hpp).
template <class Id>
std::vector<uint32_t> numbers(const std::vector<Id>& ids) {
    std::vector<uint32_t> out;
    out.reserve(ids.size());
    for (const Id id : ids) out.push_back(id.value());
    return out;
}

}  // namespace

std::vector<world::body_id> apply_tick(world::world& w, rules::rules& r, const tick_record& record) {
    std::vector<world::body_id> spawned = w.spawn_players(record.joins);
    r.on_joins(w, numbers(record.joins), numbers(spawned));
    r.on_leaves(w, numbers(record.leaves));
    w.remove_bodies(record.leaves);
    r.before_step(w, record.inputs);
    w.step(record.inputs);
    r.after_step(w);
    return spawned;
}

}  // namespace arena::match
