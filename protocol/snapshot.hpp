#pragma once
// Snapshot encoding, the hot path: the server sends one to each of up to 1000 clients
// 20 times a second. Builders are reused (no allocation once warm) and the bodies are
// copied into the buffer in one memcpy: BodyState is a fixed 32-byte little-endian struct.
#include <cstdint>
#include <span>
#include <vector>

#include "protocol/arena_generated.h"
#include "protocol/game.hpp"
#include "protocol/shapes.hpp"

namespace arena::protocol {

// No snapshot frame carries a non-finite number. The world should never produce one (config
// bounds, server/config/), but should it diverge anyway, every encoder here writes each NaN
// or infinity of a BodyState as 0, as the delta quantiser does (delta/quantize.hpp), and
// counts it: the server reports the count loudly, and a client refuses such a snapshot
// (decode_snapshot) rather than predict from it.

// The first non-finite field of `b` ("x", "y", "vx", "vy", "angle", "angular_velocity"), or
// nullptr when every field is finite.
[[nodiscard]] const char* non_finite_field(const BodyState& b) noexcept;

// Non-finite values written as 0 by every snapshot encoder of this process so far.
[[nodiscard]] std::uint64_t non_finite_values_replaced() noexcept;

// Clears fbb and encodes one finished Snapshot frame into it. Returns the frame, which lives
// in fbb and stays valid until fbb is next cleared or destroyed.
// `shapes` (optional): descriptions of bodies entering the client's view (README.md, "Shapes").
// `game` (optional): player lines, names and events (README.md, "Players and game events").
std::span<const std::uint8_t> encode_snapshot(flatbuffers::FlatBufferBuilder& fbb, std::uint32_t tick,
                                              std::uint32_t ack_sequence, std::span<const BodyState> bodies,
                                              const shape_list* shapes = nullptr, const game_list* game = nullptr);

// Clears fbb and encodes one client's delta Snapshot frame (empty bodies; `delta` holds the
// codec's bytes, protocol/delta/codec.hpp). baseline_tick 0: encoded without a baseline.
// extra_inputs_waiting: the client's inputs waiting for the world beyond the first.
std::span<const std::uint8_t> encode_delta_snapshot(flatbuffers::FlatBufferBuilder& fbb, std::uint32_t tick,
                                                    std::uint32_t ack_sequence, std::uint32_t baseline_tick,
                                                    std::span<const std::uint8_t> delta,
                                                    const shape_list* shapes = nullptr, const game_list* game = nullptr,
                                                    std::uint16_t extra_inputs_waiting = 0);

// Encodes a tick's snapshot once; each client's copy differs only in ack_sequence, which is
// patched into the copy in place. Cost per client: one memcpy of the frame.
class snapshot_encoder {
public:
    // bodies: every body, in increasing id order. Replaces the previous tick's frame.
    // shapes: descriptions every client of this frame needs (the bodies new since the last);
    // game: likewise the player lines, names and events new since the last.
    void build(std::uint32_t tick, std::span<const BodyState> bodies, const shape_list* shapes = nullptr,
               const game_list* game = nullptr);

    // The built frame with ack_sequence 0. Valid until the next build().
    [[nodiscard]] std::span<const std::uint8_t> frame() const noexcept;

    // Copies the frame into out (reusing its capacity) with ack_sequence set.
    void copy_with_ack(std::uint32_t ack_sequence, std::vector<std::uint8_t>& out) const;
    [[nodiscard]] std::vector<std::uint8_t> frame_with_ack(std::uint32_t ack_sequence) const;

private:
    flatbuffers::FlatBufferBuilder fbb_{1024};
    bool built_ = false;
};

}  // namespace arena::protocol
