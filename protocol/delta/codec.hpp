#pragma once
// Delta snapshots: one client's quantised view encoded against a view it acknowledged (its
// baseline), or in full. Bodies that match their prediction cost about one bit, changed
// bodies send only the fields that changed, new bodies are sent in full, bodies that left
// the view are listed as removed. The layout is in README.md.
//
// Views are spans of quantized_body sorted by strictly increasing id. Encoding against a
// baseline needs the decoder to hold exactly that baseline: the server keeps a ring of the
// views it sent per client and encodes against the newest one the client acknowledged.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "protocol/delta/quantize.hpp"
#include "protocol/result.hpp"

namespace arena::protocol::delta {

using view = std::span<const quantized_body>;

// How far the current view is ahead of the baseline, for the prediction of positions and
// angles (README.md, "Prediction"). Both ends must pass the same values.
struct elapsed_time {
    std::uint32_t ticks = 0;       // current tick − baseline tick; ignored for a full snapshot
    std::uint32_t tick_rate = 60;  // ticks per second (Welcome.tick_rate), > 0
};

// Appends the encoding of current to out (out is cleared first; its capacity is reused).
// baseline: the view the client acknowledged, or nullopt for a full snapshot. Both views
// must be sorted by strictly increasing id (asserted: a violation is the server's bug).
void encode(view current, std::optional<view> baseline, elapsed_time elapsed, std::vector<std::uint8_t>& out);
[[nodiscard]] std::vector<std::uint8_t> encode(view current, std::optional<view> baseline, elapsed_time elapsed);

struct decode_limits {
    std::uint32_t max_bodies = 1u << 20;  // bodies in the decoded view; matches world max_bodies
};

// What the first bytes say, without decoding the bodies: lets a client that lost its
// baseline tell a full snapshot (decodable) from a delta (not).
struct header_info {
    bool has_baseline = false;
    std::uint32_t baseline_count = 0;  // bodies the encoder's baseline had
    std::uint32_t checksum = 0;        // view_checksum() of the encoded view
};
[[nodiscard]] result<header_info> read_header(std::span<const std::uint8_t> bytes);

// Rebuilds the current view from untrusted bytes: any malformed input (truncation, trailing
// bytes, an id out of order or already present, a value out of range, a count over the
// limit, a delta without its baseline or against a different one, a checksum mismatch)
// returns a reason, never asserts, throws or reads out of bounds. baseline must be the view
// the encoder used (for a full snapshot it is ignored) and sorted by id.
[[nodiscard]] result<std::vector<quantized_body>> decode(std::span<const std::uint8_t> bytes,
                                                         std::optional<view> baseline, elapsed_time elapsed,
                                                         const decode_limits& limits = {});

// A 32-bit hash of every field of every body, in order: carried in each encoding so that a
// client decoding against the wrong baseline finds out instead of drifting silently.
[[nodiscard]] std::uint32_t view_checksum(view bodies) noexcept;

}  // namespace arena::protocol::delta
