#include "client_sim/misbehave.hpp"

#include <algorithm>
#include <cmath>

#include "protocol/version.hpp"
#include "server/world/little_endian.hpp"

namespace arena::bots {

namespace {

void put_le32(std::vector<std::uint8_t>& out, std::size_t at, std::uint32_t v) {
    world::store_le32(out.data() + at, v);
}

}  // namespace

std::optional<misbehavior> parse_misbehavior(std::string_view name) {
    if (name == "none") return misbehavior::none;
    if (name == "garbage") return misbehavior::garbage;
    if (name == "oversize") return misbehavior::oversize;
    if (name == "nan") return misbehavior::nan;
    if (name == "slow-reader") return misbehavior::slow_reader;
    if (name == "flood") return misbehavior::flood;
    if (name == "abrupt-close") return misbehavior::abrupt_close;
    return std::nullopt;
}

std::string_view to_string(misbehavior mode) {
    switch (mode) {
        case misbehavior::none:
            return "none";
        case misbehavior::garbage:
            return "garbage";
        case misbehavior::oversize:
            return "oversize";
        case misbehavior::nan:
            return "nan";
        case misbehavior::slow_reader:
            return "slow-reader";
        case misbehavior::flood:
            return "flood";
        case misbehavior::abrupt_close:
            return "abrupt-close";
    }
    return "unknown";
}

std::uint32_t misbehaving_count(std::uint32_t bots, double share) {
    if (!(share > 0) || bots == 0) return 0;
    const double wanted = std::round(static_cast<double>(bots) * std::min(share, 1.0));
    return std::clamp(static_cast<std::uint32_t>(wanted), 1u, bots);
}

bool is_misbehaving(std::uint32_t index, std::uint32_t bots, double share) {
    const std::uint64_t count = misbehaving_count(bots, share);
    if (count == 0 || index >= bots) return false;
    // Bot i is chosen when ⌊(i+1)·count/bots⌋ steps up: exactly `count` bots, evenly spaced.
    return (std::uint64_t{index} + 1) * count / bots != std::uint64_t{index} * count / bots;
}

std::vector<std::uint8_t> garbage_frame(world::rng& rng) {
    const std::uint32_t body = 8 + static_cast<std::uint32_t>(rng.next_u64() % 57);  // [8, 64]
    std::vector<std::uint8_t> frame(protocol::frame_prefix_size + body);
    put_le32(frame, 0, body);
    for (std::size_t i = protocol::frame_prefix_size; i < frame.size(); ++i)
        frame[i] = static_cast<std::uint8_t>(rng.next_u64());
    // Root offset (body bytes 0..3) beyond the body: never a valid FlatBuffer.
    put_le32(frame, protocol::frame_prefix_size, body + 4 + static_cast<std::uint32_t>(rng.next_u64() % 1024));
    std::copy_n(protocol::file_identifier, 4, frame.begin() + protocol::frame_prefix_size + 4);
    return frame;
}

std::vector<std::uint8_t> oversize_prefix() {
    std::vector<std::uint8_t> frame(protocol::frame_prefix_size + 16, 0xAB);
    put_le32(frame, 0, 1u << 20);
    return frame;
}

std::vector<std::uint8_t> half_frame(const std::vector<std::uint8_t>& frame) {
    const std::size_t keep = std::max<std::size_t>(frame.size() / 2, protocol::frame_prefix_size + 1);
    return {frame.begin(), frame.begin() + static_cast<std::ptrdiff_t>(std::min(keep, frame.size()))};
}

}  // namespace arena::bots
