#include "client_sim/hit_registration.hpp"

#include <algorithm>

namespace arena::bots {

namespace {

bool within(std::uint32_t a, std::uint32_t b, std::uint32_t window) {
    return (a > b ? a - b : b - a) <= window;
}

}  // namespace

bool hit_registration::settle(std::vector<pending>& waiting, std::uint32_t target, std::uint32_t tick) {
    const auto match = std::find_if(waiting.begin(), waiting.end(), [&](const pending& p) {
        return p.target == target && within(p.tick, tick, window_);
    });
    if (match == waiting.end()) return false;
    waiting.erase(match);
    ++counts_.confirmed;
    return true;
}

void hit_registration::claim(std::uint32_t sequence, std::uint32_t target, std::uint32_t tick) {
    if (has_claimed(sequence)) return;
    claimed_sequences_.push_back(sequence);
    // A bullet lives a few seconds at most: an old sequence cannot claim again.
    constexpr std::size_t kept = 256;
    if (claimed_sequences_.size() > kept) claimed_sequences_.erase(claimed_sequences_.begin());
    taken_.push_back(target);
    if (taken_.size() > kept) taken_.erase(taken_.begin());
    ++counts_.claimed;
    if (!settle(hits_, target, tick)) claims_.push_back({target, tick});
}

bool hit_registration::has_claimed(std::uint32_t sequence) const {
    return std::find(claimed_sequences_.begin(), claimed_sequences_.end(), sequence) != claimed_sequences_.end();
}

bool hit_registration::taken(std::uint32_t target) const {
    return std::find(taken_.begin(), taken_.end(), target) != taken_.end();
}

void hit_registration::server_hit(std::uint32_t target, std::uint32_t tick) {
    if (!settle(claims_, target, tick)) hits_.push_back({target, tick});
}

void hit_registration::other_hit(std::uint32_t target, std::uint32_t tick) {
    others_.push_back({target, tick});
}

void hit_registration::advance(std::uint32_t tick) {
    const auto closed = [&](const pending& p) {
        return p.tick + window_ < tick;
    };
    // Claimed, never confirmed: contested when something else took the target meanwhile.
    for (const pending& c : claims_) {
        if (!closed(c)) continue;
        const bool taken_by_other = std::any_of(others_.begin(), others_.end(), [&](const pending& o) {
            return o.target == c.target && within(o.tick, c.tick, window_);
        });
        counts_.contested += taken_by_other ? 1 : 0;
    }
    std::erase_if(claims_, closed);
    std::erase_if(others_, [&](const pending& o) { return o.tick + 2 * window_ < tick; });
    counts_.unclaimed_hits += static_cast<std::uint64_t>(std::erase_if(hits_, closed));
}

void hit_registration::finish(std::uint32_t tick) {
    advance(tick);
    counts_.claimed -= claims_.size();
    claims_.clear();
    counts_.unclaimed_hits += hits_.size();
    hits_.clear();
}

}  // namespace arena::bots
