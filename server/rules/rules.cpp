#include "server/rules/rules.hpp"

#include "server/rules/asteroids_rules.hpp"

namespace arena::rules {

std::unique_ptr<rules> make_rules(world::world& w) {
    switch (w.config().rules) {
        case world::game_rules::asteroids:
            return std::make_unique<asteroids_rules>(w);
        case world::game_rules::sandbox:
            break;
    }
    return std::make_unique<rules>();
}

uint64_t state_hash(const world::world& w, const rules& r) {
    if (!r.has_state()) return w.hash();
    world::fnv1a h;
    h.add_u64(w.hash());
    r.hash(h);
    return h.value();
}

}  // namespace arena::rules
