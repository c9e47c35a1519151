#include "server/net/udp_connect_gate.hpp"

#include <algorithm>
#include <vector>

#include "server/auth/key_window.hpp"
#include "server/net/enet_wire.hpp"
#include "server/net/udp_peer_commands.hpp"

namespace arena::net {

namespace {

using namespace enet_wire;

// Where the first command starts: after the header and, on a host that uses one, the checksum.
std::size_t commands_offset(const datagram_header& header, bool checksum) {
    return header.size + (checksum ? checksum_bytes : 0);
}

}  // namespace

datagram_kind classify_datagram(std::span<const std::uint8_t> datagram, bool checksum) {
    const auto header = read_datagram_header(datagram);
    if (!header) return datagram_kind::too_short;
    const std::size_t commands = commands_offset(*header, checksum);
    if (datagram.size() < commands + command_header) return datagram_kind::too_short;
    if (header->peer_id != max_peer_id) return datagram_kind::peer;
    return (datagram[commands] & command_mask) == command_connect ? datagram_kind::connect : datagram_kind::not_a_peer;
}

std::optional<std::uint32_t> connect_data(std::span<const std::uint8_t> datagram, bool checksum) {
    if (classify_datagram(datagram, checksum) != datagram_kind::connect) return std::nullopt;
    const std::size_t commands = commands_offset(*read_datagram_header(datagram), checksum);
    if (datagram.size() < commands + connect_command) return std::nullopt;
    const std::uint8_t* data = datagram.data() + commands + connect_data_offset;
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
    const std::int64_t window = auth::key_window(unix_seconds, window_s_);
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

gate_verdict connect_gate::judge_peer(std::span<const std::uint8_t> datagram, bool said_hello) {
    switch (judge_peer_commands(datagram, said_hello)) {
        case peer_commands_verdict::pass:
            return gate_verdict::pass;
        case peer_commands_verdict::before_hello:
            ++refused_before_hello_;
            return gate_verdict::refuse_before_hello;
        case peer_commands_verdict::fragment_oversize:
            ++refused_fragment_;
            return gate_verdict::refuse_fragment;
    }
    return gate_verdict::pass;
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
