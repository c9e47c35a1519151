#include "server/rules/rules.hpp"

namespace arena::rules {

std::vector<uint32_t> rules::winners() const {
    if (const uint32_t one = winner(); one != 0) return {one};
    return {};
}

uint64_t state_hash(const world::world& w, const rules& r) {
    if (!r.has_state()) return w.hash();
    world::fnv1a h;
    h.add_u64(w.hash());
    r.hash(h);
    return h.value();
}

}  // namespace arena::rules
