#pragma once
// What each body is, for drawing: the `kind` of protocol BodyShape (ship, rock, bullet...).
// The world has no notion of it; a game's rules set it when they spawn a body, and every
// body they do not tag is kind 0, a plain body. It travels with the body's shape, once per
// client (protocol/README.md, "Shapes"), so set it before the body's first snapshot: a later
// change reaches only clients that see the body afterwards for the first time.
#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "server/world/body.hpp"

namespace arena::match {

class body_kinds {
public:
    void set(uint32_t body_id, uint8_t kind) {
        const auto at = lower(body_id);
        if (at != entries_.end() && at->first == body_id) {
            at->second = kind;
        } else if (kind != 0) {
            entries_.insert(at, {body_id, kind});
        }
    }
    [[nodiscard]] uint8_t of(uint32_t body_id) const {
        const auto at = std::lower_bound(entries_.begin(), entries_.end(), body_id,
                                         [](const entry& e, uint32_t id) { return e.first < id; });
        return at != entries_.end() && at->first == body_id ? at->second : 0;
    }
    // Drops the tags of bodies no longer in `bodies` (sorted by id): ids are never reused, so
    // they would only take memory.
    void forget_missing(std::span<const world::body> bodies) {
        if (entries_.size() <= 64) return;  // not worth a pass
        size_t k = 0;
        std::erase_if(entries_, [&](const entry& e) {
            while (k < bodies.size() && bodies[k].id < e.first) ++k;
            return k == bodies.size() || bodies[k].id != e.first;
        });
    }
    [[nodiscard]] size_t size() const { return entries_.size(); }

    // How much a body of `kind` matters to a player when a snapshot cannot hold every body in
    // view, 1 to 4 (rules::snapshot_weight; snapshot_priority.hpp); 2 until set.
    void set_weight(uint8_t kind, uint8_t weight) { weights_[kind] = weight; }
    [[nodiscard]] uint8_t weight_of(uint32_t body_id) const { return weights_[of(body_id)]; }

private:
    using entry = std::pair<uint32_t, uint8_t>;
    std::vector<entry>::iterator lower(uint32_t id) {
        return std::lower_bound(entries_.begin(), entries_.end(), id,
                                [](const entry& e, uint32_t v) { return e.first < v; });
    }
    std::vector<entry> entries_;  // by increasing body id; kind 0 is not stored
    std::array<uint8_t, 256> weights_ = filled(2);

    static constexpr std::array<uint8_t, 256> filled(uint8_t weight) {
        std::array<uint8_t, 256> a{};
        a.fill(weight);
        return a;
    }
};

}  // namespace arena::match
