#pragma once
// A game's manifest (README.md, "Game manifest"): what a game declares of itself, so that a
// client built before the game existed can show its scoreboard, its events, its bodies and its
// keys. Plain values: the rules declare one (server/rules/rules.hpp), the Welcome carries it,
// the client reads it back. Every list and text has a bound, checked on both sides.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "protocol/arena_generated.h"
#include "protocol/result.hpp"

namespace arena::protocol {

inline constexpr std::size_t max_game_fields = 8;  // per player, and per team
inline constexpr std::size_t max_game_teams = 8;
inline constexpr std::size_t max_game_events = 32;  // event kinds
inline constexpr std::size_t max_event_values = 4;  // GameEventRecord.v0..v3
inline constexpr std::size_t max_body_tags = 32;
inline constexpr std::size_t max_game_inputs = 8;
inline constexpr std::size_t max_manifest_text = 64;  // bytes of any name, label, colour, key or message

struct game_field {
    std::string name;   // [a-z0-9_], 1 to 32: its key in JSON
    std::string label;  // a column's title
    GameFieldKind kind = GameFieldKind::count;
    bool operator==(const game_field&) const = default;
};

struct game_team {
    std::string name;
    std::string colour;  // CSS
    bool operator==(const game_team&) const = default;
};

struct event_spec {
    std::string name;
    std::vector<std::string> values;  // what v0..v3 hold: "player", "team", or a name of the game's
    std::string message;              // "{player} scored for {team}"
    bool operator==(const event_spec&) const = default;
};

struct body_tag {
    std::uint8_t kind = 0;  // BodyShape.kind
    std::string name;
    std::string style;   // "ship", "disc" or "" (plain)
    std::string colour;  // CSS, or "team"
    bool operator==(const body_tag&) const = default;
};

struct game_input {
    std::string name;
    std::uint8_t button = 0;  // Input.buttons bit, 0 to 7
    std::string key;          // KeyboardEvent.code
    bool operator==(const game_input&) const = default;
};

struct game_manifest {
    std::string name;  // "" : no manifest (the sandbox)
    std::vector<game_field> player_fields;
    std::vector<game_field> team_fields;
    std::vector<game_team> teams;
    std::string rank_field;  // a player field's name; "" none
    bool rank_ascending = false;
    std::vector<event_spec> events;
    std::vector<body_tag> body_tags;
    std::vector<game_input> inputs;

    [[nodiscard]] bool empty() const { return name.empty(); }
    // The index of player field `name`, or -1.
    [[nodiscard]] int player_field(std::string_view field) const;
    bool operator==(const game_manifest&) const = default;
};

// Why `m` breaks a bound or does not hold together ("player_fields[2].name: ..."), "" when it
// does. The server checks a game's manifest when it makes its rules; a client checks what it got.
[[nodiscard]] std::string manifest_problem(const game_manifest& m);

// The manifest as a GameManifest buffer of its own (Welcome.game; empty for an empty manifest),
// and back: a buffer that fails verification (its limits: max_manifest_tables tables, 4 deep)
// or breaks a bound of manifest_problem is refused with the reason.
inline constexpr std::uint32_t max_manifest_tables = 256;
[[nodiscard]] std::vector<std::uint8_t> encode_manifest(const game_manifest& m);
[[nodiscard]] result<game_manifest> decode_manifest(std::span<const std::uint8_t> buffer);

// One declared value (GameValue) and one declared event (GameEventRecord) as plain values.
struct game_value {
    std::uint32_t owner = 0;  // a player id, or a team number
    std::uint8_t field = 0;
    std::int32_t value = 0;
    bool operator==(const game_value&) const = default;
};

struct event_record {
    std::uint32_t sequence = 0;
    std::uint32_t tick = 0;
    std::uint8_t kind = 0;
    std::int32_t values[max_event_values] = {};
    bool operator==(const event_record&) const = default;
};

[[nodiscard]] GameValue to_wire(const game_value& v);
[[nodiscard]] game_value from_wire(const GameValue& v);
[[nodiscard]] GameEventRecord to_wire(const event_record& e);
[[nodiscard]] event_record from_wire(const GameEventRecord& e);

}  // namespace arena::protocol
