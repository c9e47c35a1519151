#include "server/rules/rules.hpp"

namespace arena::rules {

uint64_t state_hash(const world::world& w, const rules& r) {
    if (!r.has_state()) return w.hash();
    world::fnv1a h;
    h.add_u64(w.hash());
    r.hash(h);
    return h.value();
}

}  // namespace arena::rules
