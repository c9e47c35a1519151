#include "simnet/stream_link.hpp"

#include <algorithm>

namespace arena::simnet {

stream_link::stream_link(const conditions& c, std::uint64_t seed) : conditions_(c), dice_(seed) {}

sim_time stream_link::arrival(sim_time now) {
    ++stats_.sent;
    const sim_time sent_at = dice_.resent_until_through(conditions_, now, stats_);
    sim_time arrives = sent_at + dice_.delay(conditions_);
    // Held back in the network: later segments overtake it and wait for it at the receiver.
    const bool held = dice_.chance(conditions_.reorder);
    const sim_time extra = dice_.upto(conditions_.reorder_delay);
    if (held) {
        arrives += extra;
        ++stats_.held_back;
    }
    // A duplicate is discarded by the receiver: counted, nothing else.
    if (dice_.chance(conditions_.duplicate)) ++stats_.duplicated;
    last_readable_ = std::max(arrives, last_readable_);
    return last_readable_;
}

void stream_link::write(std::span<const std::uint8_t> bytes, sim_time now) {
    if (closed_) return;
    stats_.sent_bytes += bytes.size();
    while (!bytes.empty()) {
        const std::size_t n = std::min<std::size_t>(bytes.size(), conditions_.segment_bytes);
        const sim_time readable = arrival(now);
        segments_.push_back({readable, {bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(n)}});
        bytes = bytes.subspan(n);
    }
}

void stream_link::close(sim_time now) {
    if (closed_) return;
    closed_ = true;
    end_readable_ = arrival(now);
}

std::optional<sim_time> stream_link::next_due() const {
    if (!segments_.empty()) return segments_.front().readable;
    return end_readable_;
}

std::size_t stream_link::read(sim_time now, std::vector<std::uint8_t>& out) {
    std::size_t n = 0;
    while (!segments_.empty() && segments_.front().readable <= now) {
        const std::vector<std::uint8_t>& bytes = segments_.front().bytes;
        out.insert(out.end(), bytes.begin(), bytes.end());
        n += bytes.size();
        ++stats_.delivered;
        segments_.pop_front();
    }
    return n;
}

bool stream_link::take_end(sim_time now) {
    if (!segments_.empty() || !end_readable_ || *end_readable_ > now) return false;
    end_readable_.reset();
    return true;
}

}  // namespace arena::simnet
