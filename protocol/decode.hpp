#pragma once
// From a verified Message (verify.hpp) to plain values. Each decoder checks the payload
// type, so a message out of place gets a reason instead of a null pointer.
#include <cstdint>
#include <span>
#include <string_view>

#include "protocol/arena_generated.h"
#include "protocol/messages.hpp"
#include "protocol/result.hpp"

namespace arena::protocol {

[[nodiscard]] result<hello_msg> decode_hello(const Message& message);
[[nodiscard]] result<welcome_info> decode_welcome(const Message& message);
[[nodiscard]] result<reject_msg> decode_reject(const Message& message);
// Refuses a non-finite thrust or turn (NaN must never reach the world). Does not clamp:
// the range [-1, 1] is the server's rule, applied where inputs enter the world.
[[nodiscard]] result<input_msg> decode_input(const Message& message);
[[nodiscard]] result<ping_msg> decode_ping(const Message& message);
[[nodiscard]] result<pong_msg> decode_pong(const Message& message);
[[nodiscard]] result<bye_msg> decode_bye(const Message& message);

// A snapshot read in place: bodies points into the verified frame (no copy), so the view
// is valid as long as the frame's storage is.
struct snapshot_view {
    std::uint32_t tick = 0;
    std::uint32_t ack_sequence = 0;
    std::span<const BodyState> bodies;
    std::uint32_t baseline_tick = 0;      // delta: the view it is encoded against; 0 = none
    std::span<const std::uint8_t> delta;  // the codec's bytes (protocol/delta/codec.hpp)
    bool is_delta = false;                // the Snapshot carries `delta` (empty bodies)
    // The descriptions of bodies entering the view (README.md, "Shapes"), in the frame;
    // read_shapes() (shapes.hpp) checks and reads them. Null when absent.
    const flatbuffers::Vector<const BodyShape*>* shapes = nullptr;
    const flatbuffers::Vector<const ShapeVertex*>* shape_vertices = nullptr;
    // The table itself: read_game() (game.hpp) reads the players, names and events from it.
    const Snapshot* table = nullptr;
    // Where the bullets among `shapes` came from (README.md, "Shot origins"), every number
    // finite; empty when absent.
    std::span<const ShotOrigin> shot_origins;
    // This client's inputs waiting for the world beyond the first (README.md, "Input pacing").
    std::uint16_t extra_inputs_waiting = 0;
};
[[nodiscard]] result<snapshot_view> decode_snapshot(const Message& message);

// The body `id` of `bodies` (in increasing id order, as a snapshot's view), or null when it is
// not there: a binary search, not a scan of every body.
[[nodiscard]] const BodyState* find_body(std::span<const BodyState> bodies, std::uint32_t id);

// "Hello", "Input", ... for logs; "unknown" outside the schema.
[[nodiscard]] std::string_view payload_name(Payload type) noexcept;

}  // namespace arena::protocol
