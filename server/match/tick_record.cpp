#include "server/match/tick_record.hpp"

namespace arena::match {

std::vector<uint32_t> apply_tick(world::world& w, const tick_record& record) {
    // In one batch: spawn_player one join at a time scans every body per try (quadratic).
    std::vector<uint32_t> spawned = w.spawn_players(record.joins);
    w.remove_bodies(record.leaves);
    w.step(record.inputs);
    return spawned;
}

}  // namespace arena::match
