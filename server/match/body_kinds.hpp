#pragma once
// What each body is, for drawing: the `kind` of protocol BodyShape (ship, rock, bullet...).
// The world has no notion of it; a game's rules set it when they spawn a body, and every
// body they do not tag is kind 0, a plain body. It travels with the body's shape, once per
// client (protocol/README.md, "Shapes"). A body's kind may change during its life (the rules
// say which: rules::retagged): every change counts in `revision`, and a client that holds the
// body's shape with its old kind gets the shape again with the new one (shape_tracker.hpp).
#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "server/world/body.hpp"

namespace arena::match {

class body_kinds {
public:
    void set(uint32_t body_id, uint8_t kind) {
        const auto at = lower(body_id);
        if (at != entries_.end() && at->id == body_id) {
            if (at->kind == kind) return;
            at->kind = kind;
            at->changed = ++revision_;
        } else if (kind != 0) {
            entries_.insert(at, {body_id, kind, ++revision_});
        }
    }
    [[nodiscard]] uint8_t of(uint32_t body_id) const {
        const auto at = std::lower_bound(entries_.begin(), entries_.end(), body_id,
                                         [](const entry& e, uint32_t id) { return e.id < id; });
        return at != entries_.end() && at->id == body_id ? at->kind : 0;
    }
    // Counts every change of a kind: equal revisions, equal kinds.
    [[nodiscard]] uint64_t revision() const { return revision_; }
    // Calls f(body id) for each body whose kind changed after `revision`, in id order.
    template <class F>
    void changed_after(uint64_t revision, F&& f) const {
        if (revision == revision_) return;
        for (const entry& e : entries_)
            if (e.changed > revision) f(e.id);
    }
    // Drops the tags of bodies no longer in `bodies` (sorted by id): ids are never reused, so
    // they would only take memory.
    void forget_missing(std::span<const world::body> bodies) {
        if (entries_.size() <= 64) return;  // not worth a pass
        size_t k = 0;
        std::erase_if(entries_, [&](const entry& e) {
            while (k < bodies.size() && bodies[k].id < e.id) ++k;
            return k == bodies.size() || bodies[k].id != e.id;
        });
    }
    [[nodiscard]] size_t size() const { return entries_.size(); }

    // How much a body of `kind` matters to a player when a snapshot cannot hold every body in
    // view, 1 to 4 (rules::snapshot_weight; snapshot_priority.hpp); 2 until set.
    void set_weight(uint8_t kind, uint8_t weight) { weights_[kind] = weight; }
    [[nodiscard]] uint8_t weight_of(uint32_t body_id) const { return weights_[of(body_id)]; }

private:
    struct entry {
        uint32_t id = 0;
        uint8_t kind = 0;
        uint64_t changed = 0;  // the revision of its last change
    };
    std::vector<entry>::iterator lower(uint32_t id) {
        return std::lower_bound(entries_.begin(), entries_.end(), id,
                                [](const entry& e, uint32_t v) { return e.id < v; });
    }
    std::vector<entry> entries_;  // by increasing body id; a body never tagged (kind 0) is not stored
    uint64_t revision_ = 0;
    std::array<uint8_t, 256> weights_ = filled(2);

    static constexpr std::array<uint8_t, 256> filled(uint8_t weight) {
        std::array<uint8_t, 256> a{};
        a.fill(weight);
        return a;
    }
};

}  // namespace arena::match
