#include "client_sim/shown_view.hpp"

#include <algorithm>

#include "server/world/broadphase.hpp"

namespace arena::bots {

void shown_view::on_snapshot(std::uint32_t tick, std::uint32_t predicted, std::span<const protocol::BodyState> bodies) {
    if (!views_.empty() && tick <= views_.back().tick) return;  // overtaken: an older view adds nothing
    views_.push_back({tick, std::vector<protocol::BodyState>(bodies.begin(), bodies.end())});
    if (views_.size() > kept_views) views_.pop_front();
    // What happened before the oldest kept view is of no use any more.
    const std::uint32_t oldest = views_.front().tick;
    std::erase_if(went_, [&](const auto& e) { return e.second < oldest; });
    std::erase_if(came_, [&](const auto& e) { return e.second < oldest; });
    lags_.push_back(predicted > tick ? predicted - tick : 0);
    if (lags_.size() > kept_lags) lags_.pop_front();
    // Until the next snapshot the present runs on by up to an interval: the moment shown then
    // is still no newer than this one.
    delay_ = (*std::max_element(lags_.begin(), lags_.end()) + interval_) * 256;
}

std::uint64_t shown_view::moment(std::uint32_t predicted) const {
    if (views_.empty()) return 0;
    const std::uint64_t present = std::uint64_t{predicted} * 256;
    return present > delay_ ? present - delay_ : 0;
}

std::vector<shown_view::shown_body> shown_view::at(std::uint64_t moment, const world::world_config& config) const {
    std::vector<shown_body> out;
    if (views_.empty()) return out;
    // The first kept view at or after the moment, and the one before it.
    auto after = std::find_if(views_.begin(), views_.end(),
                              [&](const kept& v) { return std::uint64_t{v.tick} * 256 >= moment; });
    const kept& newer = after == views_.end() ? views_.back() : *after;
    const kept* older = after != views_.end() && after != views_.begin() ? &*(after - 1) : nullptr;
    // A body where it is at `moment`, carried on (or back) by its velocity from view `v`.
    const auto carried = [&](const protocol::BodyState& b, const kept& v) {
        const auto seconds = static_cast<world::real>(
            (static_cast<double>(moment) - static_cast<double>(v.tick) * 256.0) / 256.0 * config.dt);
        return shown_body{b.id(), world::vec2{b.x(), b.y()} + world::vec2{b.vx(), b.vy()} * seconds};
    };
    if (older == nullptr) {
        for (const protocol::BodyState& b : newer.bodies) out.push_back(carried(b, newer));
        return out;
    }
    // Between two views: a body in both moves from one place to the other. A body in only one
    // of them went or came between the two: it is shown while it was there, as far as the
    // server's events say when; a newcomer without a word is taken to have come with the last
    // body that went (a rock's fragments come as it goes), else with the newer view.
    const double from_moment = static_cast<double>(older->tick) * 256.0;
    const double to_moment = static_cast<double>(newer.tick) * 256.0;
    const auto t = static_cast<world::real>((static_cast<double>(moment) - from_moment) / (to_moment - from_moment));
    std::uint32_t last_went = 0;
    for (const auto& [id, tick] : went_)
        if (tick > older->tick && tick <= newer.tick) last_went = std::max(last_went, tick);
    const auto there_at = [&](const std::map<std::uint32_t, std::uint32_t>& ticks, std::uint32_t id,
                              std::uint32_t otherwise) {
        const auto it = ticks.find(id);
        return std::uint64_t{it != ticks.end() ? it->second : otherwise} * 256;
    };
    std::size_t i = 0, j = 0;
    while (i < older->bodies.size() || j < newer.bodies.size()) {
        const protocol::BodyState* a = i < older->bodies.size() ? &older->bodies[i] : nullptr;
        const protocol::BodyState* b = j < newer.bodies.size() ? &newer.bodies[j] : nullptr;
        if (a != nullptr && (b == nullptr || a->id() < b->id())) {
            // Went: shown until the tick whose state first lacks it; without a word, not at all.
            if (moment < there_at(went_, a->id(), older->tick)) out.push_back(carried(*a, *older));
            ++i;
        } else if (a == nullptr || b->id() < a->id()) {
            if (moment >= there_at(came_, b->id(), last_went != 0 ? last_went : newer.tick))
                out.push_back(carried(*b, newer));
            ++j;
        } else {
            const world::vec2 from{a->x(), a->y()};
            const world::vec2 to{b->x(), b->y()};
            out.push_back({b->id(), from + world::displacement(from, to, config) * t});
            ++i;
            ++j;
        }
    }
    return out;
}

void shown_view::went(std::uint32_t body, std::uint32_t tick) {
    went_[body] = tick;
}

void shown_view::came(std::uint32_t body, std::uint32_t tick) {
    came_[body] = tick;
}

}  // namespace arena::bots
