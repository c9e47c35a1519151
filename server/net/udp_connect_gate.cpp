#include "server/net/udp_connect_gate.hpp"

#include <algorithm>
#include <vector>

namespace arena::net {

namespace {

// ENet 1.3's wire constants (enet/protocol.h), repeated so that this file builds without ENet
// for the fuzz target.
constexpr std::uint16_t max_peer_id = 0xFFF;
constexpr std::uint16_t flag_sent_time = 1u << 15;
constexpr std::uint16_t flags_and_session = 0xF000;  // compressed, sent time, 2 session bits
constexpr std::uint8_t command_mask = 0x0F;
constexpr std::uint8_t command_connect = 2;
constexpr std::size_t command_header = 4;  // command, channel, reliable sequence number

}  // namespace

datagram_kind classify_datagram(std::span<const std::uint8_t> datagram, bool checksum) {
    if (datagram.size() < 2) return datagram_kind::too_short;
    const auto peer_field = static_cast<std::uint16_t>((datagram[0] << 8) | datagram[1]);  // network order
    std::size_t header = (peer_field & flag_sent_time) ? 4 : 2;
    if (checksum) header += 4;
    if (datagram.size() < header + command_header) return datagram_kind::too_short;
    if ((peer_field & ~flags_and_session) != max_peer_id) return datagram_kind::peer;
    return (datagram[header] & command_mask) == command_connect ? datagram_kind::connect : datagram_kind::not_a_peer;
}

gate_verdict connect_gate::judge(std::span<const std::uint8_t> datagram, const std::string& address, int64_t now_ns) {
    switch (classify_datagram(datagram)) {
        case datagram_kind::peer:
            return gate_verdict::pass;
        case datagram_kind::too_short:
        case datagram_kind::not_a_peer:
            ++refused_shape_;
            return gate_verdict::refuse_shape;
        case datagram_kind::connect:
            break;
    }
    if (datagram.size() < min_connect_datagram) {
        ++refused_shape_;
        return gate_verdict::refuse_shape;
    }
    if (buckets_.size() >= limits_.max_addresses && !buckets_.contains(address)) forget_oldest();
    if (!buckets_[address].take(now_ns, limits_.connects_per_second, limits_.burst)) {
        ++refused_rate_;
        return gate_verdict::refuse_rate;
    }
    return gate_verdict::connect;
}

void connect_gate::forget_oldest() {
    // The half refilled longest ago: a spoofed flood from many addresses costs bounded memory
    // and the gate stays O(1) per datagram on average.
    std::vector<int64_t> times;
    times.reserve(buckets_.size());
    for (const auto& [address, bucket] : buckets_) times.push_back(bucket.refilled_ns);
    auto middle = times.begin() + static_cast<std::ptrdiff_t>(times.size() / 2);
    std::nth_element(times.begin(), middle, times.end());
    const int64_t cutoff = *middle;
    std::erase_if(buckets_, [cutoff](const auto& entry) { return entry.second.refilled_ns <= cutoff; });
}

}  // namespace arena::net
