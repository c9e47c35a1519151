#pragma once
// Size-prefixed framing of a byte stream (TCP): a 4-byte little-endian body length, then the
// body. No sockets here: the reader is fed bytes, so it is tested without a network.
//
// The length is checked against the limit as soon as its 4 bytes are in, before a single
// byte of the body is buffered: a peer cannot make us allocate more than the limit.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "protocol/version.hpp"

namespace arena::protocol {

class frame_reader {
public:
    enum class state : std::uint8_t {
        need_prefix,  // waiting for (the rest of) the 4 length bytes
        need_body,    // length accepted; waiting for (the rest of) the body
        frame_ready,  // frame() holds a complete frame; call next() before reading more
        failed,       // the stream is unusable; error() says why. The connection should end.
    };
    // Why a reader failed, for a caller that answers each kind differently.
    enum class failure : std::uint8_t {
        none,
        too_large,  // the length prefix is above max_body: refused before a byte of the body
        too_small,  // the length prefix is below the smallest valid message
    };

    // max_body: the largest body accepted, in bytes (a server reading clients keeps the
    // default; a client reading the server passes max_server_frame_body).
    explicit frame_reader(std::uint32_t max_body = max_client_frame_body);

    // --- exact-count interface, for an async reader --------------------------------------
    // The bytes still missing for the current stage: the rest of the prefix, then the rest of
    // the body. Read into it (any amount up to its size), then commit() what was read. Empty
    // when a frame is ready or the reader failed.
    [[nodiscard]] std::span<std::uint8_t> next_buffer() noexcept;
    // Accepts n bytes just written into next_buffer(). n > next_buffer().size() is a caller
    // bug (asserted, then clamped).
    void commit(std::size_t n);

    // --- stream interface ----------------------------------------------------------------
    // Copies bytes in until one frame is complete or the stream fails, and returns how many
    // were consumed; feed the rest after next(). Returns 0 while a frame is ready or failed.
    std::size_t feed(std::span<const std::uint8_t> bytes);

    // --- in place ------------------------------------------------------------------------
    // A whole frame at the start of `in`, when the reader holds nothing of one and `in` starts
    // on an 8-byte boundary: returned where it lies, as frame() would hold it, without a copy
    // (most reads of a client's stream start with a whole Input). Empty otherwise, and when
    // its prefix is out of bounds: feed() those bytes, which copies them or fails as always.
    [[nodiscard]] std::span<const std::uint8_t> whole_frame_at(std::span<const std::uint8_t> in) const noexcept;

    // --- results -------------------------------------------------------------------------
    [[nodiscard]] state current() const noexcept { return state_; }
    [[nodiscard]] bool has_frame() const noexcept { return state_ == state::frame_ready; }
    [[nodiscard]] bool failed() const noexcept { return state_ == state::failed; }
    [[nodiscard]] std::string_view error() const noexcept { return error_; }
    [[nodiscard]] failure failure_kind() const noexcept { return failure_; }

    // The complete frame, prefix included, as verify_message() wants it. It starts on an
    // 8-byte boundary (FlatBuffers reads 64-bit fields in place). Valid until next().
    // Empty unless has_frame().
    [[nodiscard]] std::span<const std::uint8_t> frame() const noexcept;
    // The body alone (frame() without the 4 prefix bytes). Empty unless has_frame().
    [[nodiscard]] std::span<const std::uint8_t> body() const noexcept;

    // Bytes of the current frame held so far, prefix included (0 after next()).
    [[nodiscard]] std::size_t buffered() const noexcept { return filled_; }
    [[nodiscard]] std::uint32_t max_body() const noexcept { return max_body_; }

    // Drops the ready frame and waits for the next prefix. Keeps the storage for reuse.
    void next() noexcept;

private:
    void on_prefix_complete();
    void fail(failure kind, std::string reason);
    [[nodiscard]] std::uint8_t* bytes() noexcept;
    [[nodiscard]] const std::uint8_t* bytes() const noexcept;

    // Words, not bytes, so that the frame starts 8-byte aligned; grows to the largest frame
    // seen (at most prefix + max_body_) and never shrinks.
    std::vector<std::uint64_t> storage_;
    std::size_t filled_ = 0;       // bytes of the current frame written so far
    std::uint32_t body_size_ = 0;  // from the accepted prefix
    std::uint32_t max_body_;
    state state_ = state::need_prefix;
    failure failure_ = failure::none;
    std::string error_;
};

}  // namespace arena::protocol
