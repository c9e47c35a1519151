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
constexpr std::size_t command_header = 4;        // command, channel, reliable sequence number
constexpr std::size_t connect_command = 48;      // sizeof(ENetProtocolConnect)
constexpr std::size_t connect_data_offset = 44;  // offsetof(ENetProtocolConnect, data)

std::size_t header_size(std::span<const std::uint8_t> datagram, bool checksum) {
    const auto peer_field = static_cast<std::uint16_t>((datagram[0] << 8) | datagram[1]);  // network order
    return ((peer_field & flag_sent_time) ? 4 : 2) + (checksum ? 4 : 0);
}

// Floor division: the window of a time before the epoch is negative, as in token_secret.
std::int64_t window_of(std::int64_t unix_seconds, std::int64_t window_s) {
    return unix_seconds / window_s - (unix_seconds % window_s < 0 ? 1 : 0);
}

}  // namespace

datagram_kind classify_datagram(std::span<const std::uint8_t> datagram, bool checksum) {
    if (datagram.size() < 2) return datagram_kind::too_short;
    const auto peer_field = static_cast<std::uint16_t>((datagram[0] << 8) | datagram[1]);  // network order
    const std::size_t header = header_size(datagram, checksum);
    if (datagram.size() < header + command_header) return datagram_kind::too_short;
    if ((peer_field & ~flags_and_session) != max_peer_id) return datagram_kind::peer;
    return (datagram[header] & command_mask) == command_connect ? datagram_kind::connect : datagram_kind::not_a_peer;
}

std::optional<std::uint32_t> connect_data(std::span<const std::uint8_t> datagram, bool checksum) {
    if (classify_datagram(datagram, checksum) != datagram_kind::connect) return std::nullopt;
    const std::size_t header = header_size(datagram, checksum);
    if (datagram.size() < header + connect_command) return std::nullopt;
    const std::uint8_t* data = datagram.data() + header + connect_data_offset;
    return static_cast<std::uint32_t>(data[0]) << 24 | static_cast<std::uint32_t>(data[1]) << 16 |
           static_cast<std::uint32_t>(data[2]) << 8 | static_cast<std::uint32_t>(data[3]);
}

void connect_gate::require_connect_key(std::function<std::uint32_t(std::int64_t)> key_at, std::int64_t window_s) {
    key_at_ = std::move(key_at);
    window_s_ = std::max<std::int64_t>(1, window_s);
    keys_window_.reset();
}

void connect_gate::set_wall_clock(std::int64_t unix_seconds) {
    if (!key_at_) return;
    const std::int64_t window = window_of(unix_seconds, window_s_);
    if (keys_window_ == window) return;
    accepted_keys_ = {key_at_(unix_seconds), key_at_(unix_seconds - window_s_)};
    keys_window_ = window;
}

bool connect_gate::carries_accepted_key(std::span<const std::uint8_t> datagram) const {
    if (!keys_window_) return false;
    const auto key = connect_data(datagram);
    return key && (*key == accepted_keys_[0] || *key == accepted_keys_[1]);
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
    // Before the rate: a keyless flood spoofing an honest address does not spend its bucket,
    // and adds no address to remember.
    if (key_at_ && !carries_accepted_key(datagram)) {
        ++refused_key_;
        return gate_verdict::refuse_key;
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
