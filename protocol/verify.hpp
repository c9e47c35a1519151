#pragma once
// Checks one frame from a peer before any field is read. After verify_message() succeeds,
// every accessor of the returned Message, its payload table, strings and vectors reads
// inside the frame; before it, nothing may be read.
#include <cstdint>
#include <span>

#include "protocol/arena_generated.h"
#include "protocol/result.hpp"
#include "protocol/version.hpp"

namespace arena::protocol {

struct verify_limits {
    std::uint32_t max_body = max_client_frame_body;  // bytes after the prefix
    // A valid Message is two tables deep (Message -> payload table; vectors and strings do
    // not count). Tight limits make the Verifier's work proportional to the frame size;
    // raise them only when the schema gains nested tables.
    std::uint32_t max_depth = 4;
    std::uint32_t max_tables = 4;
};

// What a server applies to frames from clients, and a client to frames from the server.
inline constexpr verify_limits client_frame_limits{};
inline constexpr verify_limits server_frame_limits{.max_body = max_server_frame_body};

// frame: a whole size-prefixed frame (4-byte length + body), as frame_reader::frame() or an
// encode_*() function returns it. Whole, not the body alone, because FlatBuffers aligns a
// size-prefixed buffer from its first prefix byte; for the same reason frame.data() must be
// 8-byte aligned (vector and frame_reader storage are).
//
// Checks, in this order, each refusal with its own reason: size and prefix, alignment, file
// identifier "ARNA", flatbuffers::Verifier, payload type is a known message (not NONE),
// payload present. The returned pointer points into frame.
[[nodiscard]] result<const Message*> verify_message(std::span<const std::uint8_t> frame,
                                                    const verify_limits& limits = {});

}  // namespace arena::protocol
