#include "server/match/snapshot_priority.hpp"

#include <algorithm>

#include "server/world/broadphase.hpp"

namespace arena::match {

namespace {

// Within about this distance a body counts as near (m): its gain is up to four times a far one's.
constexpr float near_distance = 32.0f;

}  // namespace

uint64_t priority_accumulator::gain(uint8_t weight, float d2) {
    constexpr float n2 = near_distance * near_distance;
    // 256 far away … 1024 on top of the own body; a float expression without contraction
    // (-ffp-contract=off), so the same on every compiler.
    const float closeness = n2 / (n2 + std::max(d2, 0.0f));
    const auto distance_weight = static_cast<uint64_t>(256.0f + 768.0f * closeness);
    return std::clamp<uint64_t>(weight, 1, 4) * distance_weight;
}

void priority_accumulator::accumulate(std::span<const world::body> bodies, std::span<const uint32_t> view,
                                      uint32_t own_id, const body_kinds& kinds, const world::world_config& config) {
    const world::body* own = nullptr;
    for (const uint32_t i : view) {
        if (bodies[i].id == own_id) own = &bodies[i];
    }
    next_.clear();
    size_t k = 0;
    for (const uint32_t i : view) {
        const world::body& b = bodies[i];
        while (k < entries_.size() && entries_[k].id < b.id) ++k;
        entry e{b.id, 0, 0};
        if (k < entries_.size() && entries_[k].id == b.id) e = entries_[k];
        const float d2 = own != nullptr ? world::displacement(own->position, b.position, config).squaredNorm() : 0.0f;
        e.priority += gain(kinds.weight_of(b.id), d2);
        next_.push_back(e);
    }
    entries_.swap(next_);

    ranked_.resize(entries_.size());
    for (uint32_t p = 0; p < ranked_.size(); ++p) ranked_[p] = p;
    std::sort(ranked_.begin(), ranked_.end(), [&](uint32_t a, uint32_t b) {
        const entry& x = entries_[a];
        const entry& y = entries_[b];
        const bool x_own = x.id == own_id, y_own = y.id == own_id;
        if (x_own != y_own) return x_own;
        if (x.priority != y.priority) return x.priority > y.priority;
        return x.id < y.id;
    });
}

void priority_accumulator::sent(std::span<const uint8_t> chosen) {
    for (size_t p = 0; p < entries_.size() && p < chosen.size(); ++p) {
        if (chosen[p]) {
            entries_[p].priority = 0;
            entries_[p].left_out = 0;
        } else {
            ++entries_[p].left_out;
        }
    }
}

uint32_t priority_accumulator::most_left_out() const {
    uint32_t most = 0;
    for (const entry& e : entries_) most = std::max(most, e.left_out);
    return most;
}

const priority_accumulator::entry* priority_accumulator::find(uint32_t id) const {
    const auto at =
        std::lower_bound(entries_.begin(), entries_.end(), id, [](const entry& e, uint32_t v) { return e.id < v; });
    return at != entries_.end() && at->id == id ? &*at : nullptr;
}

uint64_t priority_accumulator::priority_of(uint32_t id) const {
    const entry* e = find(id);
    return e != nullptr ? e->priority : 0;
}

uint32_t priority_accumulator::left_out_of(uint32_t id) const {
    const entry* e = find(id);
    return e != nullptr ? e->left_out : 0;
}

}  // namespace arena::match
