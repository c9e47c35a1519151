#pragma once
// Plain C++ values for each message, and builders that produce a finished frame
// (4-byte length prefix + FlatBuffer with identifier "ARNA") ready to write to a socket.
// Snapshots, the hot path, have their own builders in snapshot.hpp.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "protocol/arena_generated.h"
#include "protocol/game.hpp"
#include "protocol/manifest.hpp"
#include "protocol/shapes.hpp"

namespace arena::protocol {

// A finished frame. std::vector storage starts 8-byte aligned, so it can be verified in place.
using frame_bytes = std::vector<std::uint8_t>;

struct hello_msg {
    std::uint16_t protocol_version = 0;
    std::string name;              // UTF-8
    std::string token;             // opaque
    bool delta_snapshots = false;  // the client decodes delta snapshots
    bool spectator = false;        // the client watches: no body, no score line
    std::string match{};           // join this match ("": see mode)
    std::string mode{};            // join-or-create a match of this mode ("" with match "": the default match)
    bool operator==(const hello_msg&) const = default;
};

struct welcome_info {
    std::uint32_t player_id = 0;
    std::uint32_t entity_id = 0;
    std::uint32_t tick = 0;
    std::uint16_t tick_rate = 0;      // ticks per second
    std::uint16_t snapshot_rate = 0;  // snapshots per second
    std::string preset;
    std::string world_config;             // JSON, the --config format
    std::uint64_t world_config_hash = 0;  // world_config_hash(world_config), config_hash.hpp
    std::uint32_t world_version = 0;
    float view_radius = 0.0f;            // m; 0 = the whole world
    std::vector<static_body> statics{};  // every static body, by increasing id (README.md, "Shapes")
    std::string match{};                 // the id of the match joined
    std::string mode{};                  // the mode it plays
    game_manifest game{};                // what the game declares of itself; empty: nothing
    bool operator==(const welcome_info&) const = default;
};

struct reject_msg {
    RejectCode code = RejectCode::bad_request;
    std::string reason;
    bool operator==(const reject_msg&) const = default;
};

// An earlier input repeated in a later Input (Input.earlier): see protocol/README.md.
struct earlier_input {
    std::uint32_t sequence = 0;
    float thrust = 0.0f;
    float turn = 0.0f;
    std::uint8_t buttons = 0;
    bool operator==(const earlier_input&) const = default;
};
// The most earlier inputs one Input may carry.
inline constexpr std::size_t max_earlier_inputs = 8;

struct input_msg {
    std::uint32_t sequence = 0;
    float thrust = 0.0f;                   // [-1, 1]
    float turn = 0.0f;                     // [-1, 1]
    std::uint8_t buttons = 0;              // bit 0 = impulse/jump
    std::uint32_t snapshot_ack = 0;        // newest delta snapshot tick decoded; 0 = none
    std::vector<earlier_input> earlier{};  // oldest first, each sequence below `sequence`
    std::uint32_t view_tick = 0;           // the tick of the view the client showed; 0 = not told
    std::uint8_t view_fraction = 0;        // and 1/256 ticks past it
    bool operator==(const input_msg&) const = default;
};

struct ping_msg {
    std::uint64_t client_time = 0;
    bool operator==(const ping_msg&) const = default;
};

struct pong_msg {
    std::uint64_t client_time = 0;
    std::uint32_t server_tick = 0;
    std::optional<std::uint32_t> server_hold_us{};  // µs the Ping waited at the server; none: not measured
    bool operator==(const pong_msg&) const = default;
};

struct bye_msg {
    std::string reason;
    match_result result{};  // the end of a match: the winner and the final scoreboard
    bool operator==(const bye_msg&) const = default;
};

// Input bits.
inline constexpr std::uint8_t button_impulse = 1u << 0;

[[nodiscard]] frame_bytes encode_hello(std::uint16_t version, std::string_view name, std::string_view token,
                                       bool delta_snapshots = false, bool spectator = false);
[[nodiscard]] frame_bytes encode_hello(const hello_msg& hello);
[[nodiscard]] frame_bytes encode_welcome(const welcome_info& welcome);
[[nodiscard]] frame_bytes encode_reject(RejectCode code, std::string_view reason);
[[nodiscard]] frame_bytes encode_input(const input_msg& input);
// The Input table of `input` in a builder (encode_input, and a client's reused builder).
flatbuffers::Offset<Input> create_input(flatbuffers::FlatBufferBuilder& fbb, const input_msg& input);
[[nodiscard]] frame_bytes encode_ping(std::uint64_t client_time);
[[nodiscard]] frame_bytes encode_pong(std::uint64_t client_time, std::uint32_t server_tick,
                                      std::optional<std::uint32_t> server_hold_us = std::nullopt);
// `result` (optional): the match is over (README.md, "Players and game events").
[[nodiscard]] frame_bytes encode_bye(std::string_view reason, const match_result* result = nullptr);

// Wraps a finished payload table in a Message and finishes the buffer size-prefixed with
// the file identifier. For builders that encode into a caller-owned FlatBufferBuilder.
void finish_message(flatbuffers::FlatBufferBuilder& fbb, Payload type, flatbuffers::Offset<void> payload);

}  // namespace arena::protocol
