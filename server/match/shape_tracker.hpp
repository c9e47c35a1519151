#pragma once
// Which body shapes one client holds, so that each snapshot describes exactly the bodies of
// its view the client may lack (protocol/README.md, "Shapes"). The rule, for links that lose
// and reorder frames as well as for streams:
// - a body is *known* once the client acknowledged (Input.snapshot_ack) a snapshot sent since
//   the body last entered its view: that snapshot described it, and the client keeps a shape
//   while the body stays in its newest view;
// - every snapshot describes each body of its view that is not known yet, so whichever
//   snapshot the client decodes, it holds the shape of every body in it;
// - a body that leaves the view is forgotten on both sides; when it comes back it is
//   described again;
// - a body whose kind changed (body_kinds.hpp) is no longer known: it is described again
//   with its new kind, under the same rule, and the client replaces the shape it held.
// On a reliable stream without acknowledgements (clients of full BodyState snapshots) a
// description sent is held: `reliable` makes a body known at once. Static bodies whose ids
// the Welcome covered are never described: the Welcome carried them all.
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "server/match/body_kinds.hpp"
#include "server/world/body.hpp"

namespace arena::match {

class shape_tracker {
public:
    // The Welcome carried every static body with an id below `below`.
    void welcomed(uint32_t below) {
        statics_below_ = below;
        known_.clear();
        pending_.clear();
        last_view_.clear();
        last_bodies_ = {};
        last_revision_ = 0;
    }

    // One snapshot at `tick` holding bodies[i] for each i of `view` (increasing indices of a
    // span sorted by id). `acked`: the newest snapshot tick the client acknowledged, which
    // must be one sent to it (0: none). `kinds`: what each body is now. Calls describe(i) for
    // each body to describe, in order.
    template <class Describe>
    void update(uint32_t tick, std::span<const world::body> bodies, std::span<const uint32_t> view, uint32_t acked,
                bool reliable, const body_kinds& kinds, Describe&& describe) {
        // The common case, every body of the view known and the view and kinds as before,
        // costs a comparison: ids grow and are never reused, so the same count and the same
        // newest id mean the same bodies at the same indices.
        const body_set now = bodies.empty() ? body_set{} : body_set{bodies.size(), bodies.back().id};
        if (pending_.empty() && now == last_bodies_ && kinds.revision() == last_revision_ &&
            std::equal(view.begin(), view.end(), last_view_.begin(), last_view_.end()))
            return;
        const bool retagged = kinds.revision() != last_revision_;
        last_bodies_ = now;
        last_revision_ = kinds.revision();
        last_view_.assign(view.begin(), view.end());
        next_known_.clear();
        next_pending_.clear();
        size_t k = 0, p = 0;
        for (const uint32_t i : view) {
            const world::body& b = bodies[i];
            if (b.is_static() && b.id < statics_below_) continue;  // the Welcome's: tagged for good
            // Kinds are looked up only when one changed since the last update.
            const auto kind_now = [&](uint8_t as_held) {
                return retagged ? kinds.of(b.id) : as_held;
            };
            while (k < known_.size() && known_[k].id < b.id) ++k;
            if (k < known_.size() && known_[k].id == b.id) {
                const uint8_t kind = kind_now(known_[k].kind);
                if (kind == known_[k].kind) {
                    next_known_.push_back(known_[k]);
                    continue;
                }
            }
            while (p < pending_.size() && pending_[p].id < b.id) ++p;
            const uint8_t kind = kinds.of(b.id);
            // Entered anew when it was not pending, or was described with another kind since.
            const bool was_pending = p < pending_.size() && pending_[p].id == b.id && pending_[p].kind == kind;
            const uint32_t entered = was_pending ? pending_[p].entered : tick;
            if (was_pending && acked != 0 && entered <= acked) {
                next_known_.push_back({b.id, kind});  // a snapshot that described it arrived
                continue;
            }
            describe(i);
            if (reliable) {
                next_known_.push_back({b.id, kind});
            } else {
                next_pending_.push_back({b.id, entered, kind});
            }
        }
        known_.swap(next_known_);
        pending_.swap(next_pending_);
    }

    [[nodiscard]] size_t known() const { return known_.size(); }
    [[nodiscard]] size_t pending() const { return pending_.size(); }

private:
    struct body_set {
        size_t count = 0;
        uint32_t newest_id = 0;
        bool operator==(const body_set&) const = default;
    };
    struct held {
        uint32_t id = 0;
        uint8_t kind = 0;  // as described
    };
    struct waiting {
        uint32_t id = 0;
        uint32_t entered = 0;  // the first snapshot tick describing it as it is (its kind)
        uint8_t kind = 0;      // as described
    };
    uint32_t statics_below_ = 0;
    std::vector<held> known_;       // increasing ids
    std::vector<waiting> pending_;  // increasing ids
    std::vector<held> next_known_;
    std::vector<waiting> next_pending_;
    body_set last_bodies_;             // the world's bodies at the last update
    uint64_t last_revision_ = 0;       // and their kinds' revision
    std::vector<uint32_t> last_view_;  // and the view it was for
};

}  // namespace arena::match
