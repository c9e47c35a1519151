#include "simnet/datagram_link.hpp"

#include <algorithm>

namespace arena::simnet {

datagram_link::datagram_link(const conditions& c, std::uint64_t seed) : conditions_(c), dice_(seed) {}

void datagram_link::put(std::span<const std::uint8_t> message, sim_time arrives) {
    flight_.push_back({arrives, next_order_++, {message.begin(), message.end()}});
    std::push_heap(flight_.begin(), flight_.end(), later{});
}

void datagram_link::send(std::span<const std::uint8_t> message, sim_time now) {
    ++stats_.sent;
    stats_.sent_bytes += message.size();
    // Every draw is made whatever the outcome, in a fixed order, so that one message's fate
    // does not shift the draws of the next.
    const bool lost = dice_.chance(conditions_.loss);
    sim_time arrives = now + dice_.delay(conditions_);
    const bool held = dice_.chance(conditions_.reorder);
    const sim_time extra = dice_.upto(conditions_.reorder_delay);
    const bool twice = dice_.chance(conditions_.duplicate);
    const sim_time copy_arrives = now + dice_.delay(conditions_) + dice_.upto(conditions_.latency);
    if (lost || blocked(now)) {
        ++stats_.lost;
        return;
    }
    if (held) {
        arrives += extra;
        ++stats_.held_back;
    }
    put(message, arrives);
    if (twice) {
        ++stats_.duplicated;
        put(message, copy_arrives);
    }
}

void datagram_link::send_reliable(std::span<const std::uint8_t> message, sim_time now) {
    ++stats_.sent;
    stats_.sent_bytes += message.size();
    sim_time sent_at = dice_.resent_until_through(conditions_, now, stats_);
    for (sim_time timeout = conditions_.retransmit_timeout; blocked(sent_at);
         timeout = std::min(2 * timeout, conditions_.max_retransmit_timeout)) {
        ++stats_.lost;
        ++stats_.retransmissions;
        sent_at += timeout;
    }
    // In order among the reliable messages: one that arrives early waits for those before it.
    last_reliable_ = std::max(sent_at + dice_.delay(conditions_), last_reliable_);
    put(message, last_reliable_);
}

std::optional<sim_time> datagram_link::next_due() const {
    if (flight_.empty()) return std::nullopt;
    return flight_.front().arrives;
}

bool datagram_link::receive(sim_time now, std::vector<std::uint8_t>& out) {
    if (flight_.empty() || flight_.front().arrives > now) return false;
    std::pop_heap(flight_.begin(), flight_.end(), later{});
    out = std::move(flight_.back().bytes);
    flight_.pop_back();
    ++stats_.delivered;
    return true;
}

}  // namespace arena::simnet
