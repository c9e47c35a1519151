#pragma once
// Fault injection: what a misbehaving bot sends, so that the server's refusal paths
// (protocol/README.md, "Server rules") can be exercised against a live server. Frame
// builders only; bot.cpp decides when to send them.
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "server/world/rng.hpp"

namespace arena::bots {

enum class misbehavior : std::uint8_t {
    none,
    garbage,       // a frame with a small, valid length prefix and a body that is no FlatBuffer
    oversize,      // a length prefix above the 64 KiB client limit
    nan,           // an Input whose thrust is NaN
    slow_reader,   // never reads its socket after joining, keeps sending inputs
    flood,         // sends inputs far above the tick rate
    abrupt_close,  // writes half of a frame, then closes the connection
};

std::optional<misbehavior> parse_misbehavior(std::string_view name);
std::string_view to_string(misbehavior mode);

// How many of `bots` misbehave with this share: round(bots · share), at least one when the
// share is above zero, so that `--misbehave` on a handful of bots still does something.
std::uint32_t misbehaving_count(std::uint32_t bots, double share);
// Whether bot `index` is one of them. They are spread evenly over the indices (not the
// first ones), so that with --behavior mixed they cover every behaviour.
bool is_misbehaving(std::uint32_t index, std::uint32_t bots, double share);

// Inputs a flooding bot sends per tick: 20× the tick rate, far above any sane limit.
inline constexpr std::uint32_t flood_inputs_per_tick = 20;
// A misbehaving bot first plays normally for this many ticks (0.5 s at 60 Hz), so that the
// server meets the fault in a joined session, the case that must not disturb other players.
inline constexpr std::uint32_t misbehave_after_ticks = 30;

// 4-byte length prefix (8..64) and a random body. Bytes 4..7 spell "ARNA", so the frame
// passes the identifier check and reaches the FlatBuffers verifier; the root offset points
// past the end, so the verifier always refuses it (random bytes could, once in 2^32, be valid).
std::vector<std::uint8_t> garbage_frame(world::rng& rng);
// A length prefix of 1 MiB followed by a few body bytes: refused from the prefix alone.
std::vector<std::uint8_t> oversize_prefix();
// The first half of `frame` (at least its prefix and one byte): a frame cut off mid-body.
std::vector<std::uint8_t> half_frame(const std::vector<std::uint8_t>& frame);

}  // namespace arena::bots
