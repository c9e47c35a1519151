#pragma once
// Game rules: what a match means (who scores, who dies, what spawns), between the match and
// the world. The match calls them every tick through apply_tick (server/match/tick_record.hpp),
// and the replay calls the same function, so a recording reproduces the rules' state bit for
// bit. Rules change the world only through the calls below, between steps; they read no clock
// and do no I/O (tests/layers checks this folder like the world and the match).
//
// A game brings its own rules by deriving from `rules` in its folder, games/NAME/, and
// registering itself there (game.hpp; docs/GAMES.md).
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "protocol/manifest.hpp"
#include "server/world/hash.hpp"
#include "server/world/input.hpp"
#include "server/world/world.hpp"

namespace arena::rules {

// What a player is doing in the game (protocol PlayerState).
enum class player_state : uint8_t { playing, respawning, out };

// One player's line of the scoreboard.
struct score_line {
    uint32_t player = 0;  // player id (the owner of its bodies)
    uint32_t score = 0;
    uint32_t kills = 0;
    uint32_t deaths = 0;
    uint32_t shots = 0;
    uint32_t hits = 0;
    uint32_t lives = 0;
    bool out = false;  // no lives left, or left the match
    player_state state = player_state::playing;
    uint8_t team = 0;  // the player's team (teams()), 0 in a game without teams
    // The game's own values for this player, in the order of its manifest's player_fields.
    std::array<int32_t, protocol::max_game_fields> values{};
};

// One team's line: its number (score_line.team), its name and its score.
struct team_line {
    uint8_t team = 0;
    std::string name;
    uint32_t score = 0;
    // The game's own values for this team, in the order of its manifest's team_fields.
    std::array<int32_t, protocol::max_game_fields> values{};
    bool operator==(const team_line&) const = default;
};

// One of the game's own events: the index of its kind in the manifest's events, and the values
// that kind declares, in order.
struct declared_event {
    uint8_t kind = 0;
    std::array<int32_t, protocol::max_event_values> values{};
    bool operator==(const declared_event&) const = default;
};

// Something that happened in a step, for the players to hear (protocol GameEvent; the
// match numbers them). The rules define what each field means per kind.
enum class event_kind : uint8_t { rock_hit, ship_destroyed, respawn, wave, shot_rewound };
struct game_event {
    event_kind kind = event_kind::rock_hit;
    uint8_t size = 0;     // rock_hit: the rock's size
    uint32_t player = 0;  // whom it happened to, or who did it
    uint32_t other = 0;   // ship_destroyed: the shooter (0: a rock)
    uint32_t body = 0;    // the rock hit, the ship lost, the new ship
    uint32_t value = 0;   // points scored; wave: its rocks; shot_rewound: the rewind, 1/256 ticks
    bool operator==(const game_event&) const = default;
};

// A bullet's shooter and its state as it spawned, before the world's step moved it: what a
// client that predicts its own shots compares its prediction with (protocol ShotOrigin).
struct shot_record {
    uint32_t shooter = 0;        // player id
    world::vec2 position{0, 0};  // m
    world::vec2 velocity{0, 0};  // m/s
};

class rules {
public:
    virtual ~rules() = default;

    // The bodies world::spawn_players gave the tick's joins (0: the world was full).
    virtual void on_joins(world::world&, std::span<const uint32_t> /*owners*/, std::span<const uint32_t> /*bodies*/) {}
    // Bodies the match is about to remove because their players left.
    virtual void on_leaves(world::world&, std::span<const uint32_t> /*bodies*/) {}
    // Before the step, with the inputs it will apply (in any order): fire, spawn, push.
    virtual void before_step(world::world&, const world::tick_inputs& /*inputs*/) {}
    // After the step: read world::contact_events(), remove and spawn bodies, keep score.
    virtual void after_step(world::world&) {}

    // The body `player` controls now, or 0 when it has none of the rules' making (sandbox
    // rules: the body the match spawned stays the player's).
    virtual uint32_t body_of(uint32_t /*player*/) const { return 0; }
    // What body `id` is, for drawing (protocol BodyShape.kind: the game defines the values);
    // 0 = a plain body. The match asks in the tick the body appears, and again after any step
    // that lists the body in take_retagged().
    virtual uint8_t kind_of(uint32_t /*body_id*/) const { return 0; }
    // Appends to `into` the bodies whose kind_of changed since the last call, and forgets them
    // (derived from the state: not hashed). The match calls it once a tick, after the step;
    // clients that hold such a body's shape get it again with its new kind.
    virtual void take_retagged(std::vector<uint32_t>& /*into*/) {}
    // How much a body of `kind` matters to a player when a snapshot cannot hold every body in
    // view (server/match/snapshot_priority.hpp): 1 (it moves predictably, as a drifting rock) to
    // 4 (another player's body). Plain bodies are 2.
    virtual uint8_t snapshot_weight(uint8_t /*kind*/) const { return 2; }
    // Where body `id` was fired from, when it is a live shot (the match asks in the tick it
    // appears); null for any other body.
    virtual const shot_record* shot_of(uint32_t /*body_id*/) const { return nullptr; }
    // False: the rules keep no state, and the state hash is the world's own.
    virtual bool has_state() const { return false; }
    // Every field of the rules' state, in a fixed order.
    virtual void hash(world::fnv1a&) const {}
    // Players in id order (empty for sandbox rules).
    virtual std::vector<score_line> scoreboard() const { return {}; }
    // What happened in the last after_step, in order (derived from the state: not hashed).
    virtual std::span<const game_event> events() const { return {}; }
    // What the game declares of itself for the wire (protocol/manifest.hpp): its fields, teams,
    // events, body tags and inputs; empty for a game that declares nothing. Asked once per match.
    virtual protocol::game_manifest manifest() const { return {}; }
    // The game's own events of the last after_step, in order (manifest().events; not hashed).
    virtual std::span<const declared_event> declared_events() const { return {}; }
    // The player winning now, as this game decides it; 0 = nobody (a tie, a team game, or no game).
    virtual uint32_t winner() const { return 0; }
    // The teams and their scores, in team order (empty in a game without teams).
    virtual std::vector<team_line> teams() const { return {}; }
    // The team winning now; 0 = none (a draw, or no teams).
    virtual uint8_t winning_team() const { return 0; }
    // The players winning now: the winning team's, or every player tied at the top; empty:
    // nobody. By default winner() alone.
    virtual std::vector<uint32_t> winners() const;
    // True once the rules have ended the match (a clock ran out): the match says Bye to
    // everyone with the result, as at --score-limit.
    virtual bool finished() const { return false; }
};

// The hash recordings and replays compare: the world's, followed by the rules' state when
// they have any (so sandbox worlds keep the hashes they always had).
uint64_t state_hash(const world::world& w, const rules& r);

}  // namespace arena::rules
