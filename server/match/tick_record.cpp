#include "server/match/tick_record.hpp"

namespace arena::match {

std::vector<uint32_t> apply_tick(world::world& w, const tick_record& record) {
    // In one batch: spawn_player one join at a time scans every body per try (quadratic).
    std::vector<uint32_t> spawned = w.spawn_players(record.joins);
    w.remove_bodies(record.leaves);
    w.step(record.inputs);
    return spawned;
}

std::vector<uint32_t> apply_tick(world::world& w, rules::rules& r, const tick_record& record) {
    std::vector<uint32_t> spawned = w.spawn_players(record.joins);
    r.on_joins(w, record.joins, spawned);
    r.on_leaves(w, record.leaves);
    w.remove_bodies(record.leaves);
    r.before_step(w, record.inputs);
    w.step(record.inputs);
    r.after_step(w);
    return spawned;
}

}  // namespace arena::match
