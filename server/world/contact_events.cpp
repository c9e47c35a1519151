#include "server/world/contact_events.hpp"

#include <algorithm>

namespace arena::world {

namespace {

// The velocity of `b`'s material at `anchor` from its centre: v + ω × r.
vec2 point_velocity(const body& b, const vec2& anchor) {
    return b.velocity + vec2{-b.angular_velocity * anchor.y(), b.angular_velocity * anchor.x()};
}

}  // namespace

void contact_event_tracker::measure_approach(std::span<const body> bodies, std::span<const contact> contacts) {
    approach_.assign(contacts.size(), 0);
    for (size_t k = 0; k < contacts.size(); ++k) {
        const contact& c = contacts[k];
        if (c.with != wall::none || c.count == 0) continue;
        const contact_point& p = c.points[0];
        const vec2 relative = point_velocity(bodies[c.b], p.anchor_b) - point_velocity(bodies[c.a], p.anchor_a);
        approach_[k] = -relative.dot(c.normal);
    }
}

void contact_event_tracker::collect(std::span<const body> bodies, std::span<const contact> contacts, bool sub_stepped) {
    events_.clear();
    now_.clear();
    for (size_t k = 0; k < contacts.size(); ++k) {
        const contact& c = contacts[k];
        if (c.with != wall::none) continue;
        real impulse = 0;
        for (int i = 0; i < c.count; ++i)
            impulse += sub_stepped ? c.points[i].step_impulse : c.points[i].normal_impulse;
        if (!(c.separation <= 0 || impulse > 0)) continue;
        const body& a = bodies[c.a];
        const body& b = bodies[c.b];
        const bool swap = a.id > b.id;  // static pairs list the moving body first
        const uint32_t lo = swap ? b.id : a.id;
        const uint32_t hi = swap ? a.id : b.id;
        const uint64_t key = uint64_t{lo} << 32 | hi;
        now_.push_back(key);
        if (std::binary_search(touching_.begin(), touching_.end(), key)) continue;
        const real approach = k < approach_.size() ? approach_[k] : 0;
        events_.push_back({lo, hi, swap ? vec2(-c.normal) : c.normal, approach, impulse});
    }
    // Keys are unique (one contact per pair): sorting them is a total order.
    std::sort(now_.begin(), now_.end());
    std::sort(events_.begin(), events_.end(),
              [](const contact_event& l, const contact_event& r) { return l.a != r.a ? l.a < r.a : l.b < r.b; });
    touching_.swap(now_);
}

void contact_event_tracker::reset() {
    touching_.clear();
    events_.clear();
}

}  // namespace arena::world
