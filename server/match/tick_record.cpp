#include "server/match/tick_record.hpp"

namespace arena::match {

std::vector<uint32_t> apply_tick(world::world& w, const tick_record& record) {
    std::vector<uint32_t> spawned;
    spawned.reserve(record.joins.size());
    for (uint32_t owner : record.joins) spawned.push_back(w.spawn_player(owner).value_or(0));
    for (uint32_t body_id : record.leaves) w.remove_body(body_id);
    w.step(record.inputs);
    return spawned;
}

}  // namespace arena::match
