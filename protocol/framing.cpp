#include "protocol/framing.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "server/world/assert.hpp"
#include "server/world/little_endian.hpp"

namespace arena::protocol {

frame_reader::frame_reader(std::uint32_t max_body)
    : storage_(1),  // room for the prefix before any body is accepted
      max_body_(max_body) {}

std::uint8_t* frame_reader::bytes() noexcept {
    // Writing a uint64_t's bytes through unsigned char is always allowed.
    return reinterpret_cast<std::uint8_t*>(storage_.data());
}

const std::uint8_t* frame_reader::bytes() const noexcept {
    return reinterpret_cast<const std::uint8_t*>(storage_.data());
}

std::span<std::uint8_t> frame_reader::next_buffer() noexcept {
    switch (state_) {
        case state::need_prefix:
            return {bytes() + filled_, frame_prefix_size - filled_};
        case state::need_body:
            return {bytes() + filled_, frame_prefix_size + body_size_ - filled_};
        case state::frame_ready:
        case state::failed:
            break;
    }
    return {};
}

void frame_reader::commit(std::size_t n) {
    const std::size_t room = next_buffer().size();
    ARENA_ASSERT(n <= room, "commit() of more bytes than next_buffer() offered");
    filled_ += std::min(n, room);
    if (state_ == state::need_prefix && filled_ == frame_prefix_size) {
        on_prefix_complete();
    }
    if (state_ == state::need_body && filled_ == frame_prefix_size + body_size_) {
        state_ = state::frame_ready;
    }
}

std::size_t frame_reader::feed(std::span<const std::uint8_t> in) {
    std::size_t consumed = 0;
    // At most two rounds (prefix, body); stops early on a ready frame or a failure.
    for (auto dest = next_buffer(); !dest.empty() && consumed < in.size(); dest = next_buffer()) {
        const std::size_t n = std::min(dest.size(), in.size() - consumed);
        std::memcpy(dest.data(), in.data() + consumed, n);
        consumed += n;
        commit(n);
    }
    return consumed;
}

std::span<const std::uint8_t> frame_reader::whole_frame_at(std::span<const std::uint8_t> in) const noexcept {
    if (state_ != state::need_prefix || filled_ != 0 || in.size() < frame_prefix_size ||
        reinterpret_cast<std::uintptr_t>(in.data()) % alignof(std::uint64_t) != 0)
        return {};
    const std::uint32_t length = world::load_le32(in.data());
    if (length > max_body_ || length < min_frame_body || in.size() - frame_prefix_size < length) return {};
    return in.first(frame_prefix_size + std::size_t{length});
}

void frame_reader::on_prefix_complete() {
    const std::uint8_t* p = bytes();
    // Little-endian on the wire whatever the host.
    const std::uint32_t length = world::load_le32(p);
    if (length > max_body_) {
        fail(failure::too_large, "frame length " + std::to_string(length) + " exceeds the limit of " +
                                     std::to_string(max_body_) + " bytes");
        return;
    }
    if (length < min_frame_body) {
        fail(failure::too_small, "frame length " + std::to_string(length) + " is below the minimum of " +
                                     std::to_string(min_frame_body) + " bytes");
        return;
    }
    body_size_ = length;
    const std::size_t words = (frame_prefix_size + std::size_t{length} + 7) / 8;
    if (storage_.size() < words) storage_.resize(words);  // keeps the prefix bytes
    state_ = state::need_body;
}

void frame_reader::fail(failure kind, std::string reason) {
    state_ = state::failed;
    failure_ = kind;
    error_ = std::move(reason);
}

std::span<const std::uint8_t> frame_reader::frame() const noexcept {
    if (state_ != state::frame_ready) return {};
    return {bytes(), frame_prefix_size + std::size_t{body_size_}};
}

std::span<const std::uint8_t> frame_reader::body() const noexcept {
    return frame().subspan(has_frame() ? frame_prefix_size : 0);
}

void frame_reader::next() noexcept {
    if (state_ == state::failed) return;  // a failed stream stays failed
    state_ = state::need_prefix;
    filled_ = 0;
    body_size_ = 0;
}

}  // namespace arena::protocol
