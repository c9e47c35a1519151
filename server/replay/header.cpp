#include "server/replay/header.hpp"

#include <utility>

#include "server/config/config_json.hpp"

namespace arena::replay {

header make_header(const world::world& w, std::string preset, uint64_t seed, uint32_t tick_rate,
                   uint32_t hash_interval) {
    header h;
    h.world_config = config::config_to_json(w.config());
    h.preset = std::move(preset);
    h.seed = seed;
    h.tick_rate = tick_rate;
    h.hash_interval = hash_interval;
    h.start_tick = w.tick();
    h.start_hash = w.hash();
    return h;
}

}  // namespace arena::replay
