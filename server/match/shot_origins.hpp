#pragma once
// Where each live bullet came from (protocol ShotOrigin): its shooter, the shooter's input
// that fired it, and its spawn state. The match records it in the tick the bullet appears
// (the input consumed in that tick is the one that fired), and the fan-out sends it with the
// bullet's shape, so once per client as the bullet first enters its view (body_kinds.hpp).
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "protocol/arena_generated.h"
#include "server/world/body.hpp"

namespace arena::match {

class shot_origins {
public:
    // Bodies get ids in increasing order: a new bullet goes at the end.
    void add(const protocol::ShotOrigin& origin) {
        if (!entries_.empty() && entries_.back().body_id() >= origin.body_id()) return;
        entries_.push_back(origin);
    }
    // Body `id`'s origin, or null when it is no bullet of a player.
    [[nodiscard]] const protocol::ShotOrigin* of(uint32_t body_id) const {
        const auto at = std::lower_bound(entries_.begin(), entries_.end(), body_id,
                                         [](const protocol::ShotOrigin& o, uint32_t id) { return o.body_id() < id; });
        return at != entries_.end() && at->body_id() == body_id ? &*at : nullptr;
    }
    // Drops the origins of bodies no longer in `bodies` (sorted by id): bullets live about a
    // second, and ids are never reused.
    void forget_missing(std::span<const world::body> bodies) {
        size_t k = 0;
        std::erase_if(entries_, [&](const protocol::ShotOrigin& o) {
            while (k < bodies.size() && bodies[k].id < o.body_id()) ++k;
            return k == bodies.size() || bodies[k].id != o.body_id();
        });
    }
    [[nodiscard]] size_t size() const { return entries_.size(); }

private:
    std::vector<protocol::ShotOrigin> entries_;  // by increasing body id
};

}  // namespace arena::match
