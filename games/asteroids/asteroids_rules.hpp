#pragma once
// Asteroids as the arcade game plays, on the lecture's physics (the impulse J changes a
// velocity by J/m at once, both ways):
// - Fire (Input.buttons bit 1): a bullet leaves the ship's nose with the impulse J along the
//   facing (Δv = J/m_bullet on top of the ship's velocity) and the ship recoils by −J
//   (Δv = −J/m_ship). A cooldown, a lifetime and a cap on live bullets per ship. Bullets pass
//   through their shooter (a shared negative filter group) and each other (masks).
// - Rocks: a bullet that hits a rock removes both; large splits into two medium, medium into
//   two small, small is gone. The pieces share the rock's mass and leave symmetrically about
//   its velocity with a split impulse (momentum conserved). 20, 50, 100 points. When every
//   rock is gone, a wave of one more large rock than the last spawns away from the ships.
// - Ships: hit by a rock or another player's bullet, a ship loses a life and its body goes;
//   it respawns at a free spot 120 ticks later, passing through everything for 120 ticks.
//   Three lives (ships after the first), so the fourth death puts the player out for the rest
//   of the match. Shooting a ship scores 200.
#include <cstdint>
#include <map>
#include <vector>

#include "games/asteroids/asteroids_shot.hpp"
#include "server/rules/hit_history.hpp"
#include "server/rules/rules.hpp"
#include "server/world/rng.hpp"

namespace arena::rules {

// BodyShape.kind of the game's bodies (protocol/README.md); a rock's size is in its shape.
inline constexpr uint8_t kind_ship = 1;
inline constexpr uint8_t kind_rock = 2;
inline constexpr uint8_t kind_bullet = 3;

// The kind (its index in the manifest's events) of the one event Asteroids declares.
inline constexpr uint8_t judged_in_past = 0;

class asteroids_rules : public rules {
public:
    // Every moving body of `w` without an owner is a large rock; contact events go on.
    explicit asteroids_rules(world::world& w, const asteroids_params& params = {});

    void on_joins(world::world& w, std::span<const uint32_t> owners, std::span<const uint32_t> bodies) override;
    void on_leaves(world::world& w, std::span<const uint32_t> bodies) override;
    void before_step(world::world& w, const world::tick_inputs& inputs) override;
    void after_step(world::world& w) override;

    uint32_t body_of(uint32_t player) const override;
    uint8_t kind_of(uint32_t body_id) const override;
    // Ships matter most (other players), bullets next (fast, short-lived), plain bodies, then
    // rocks (they drift: a client's prediction of a left-out rock stays right longest).
    uint8_t snapshot_weight(uint8_t kind) const override;
    bool has_state() const override { return true; }
    void hash(world::fnv1a& h) const override;
    std::vector<score_line> scoreboard() const override;
    std::span<const game_event> events() const override { return events_; }
    // The one event it declares (manifest()): `judged_in_past`, a hit judged against the past,
    // with the target's bounding circle where the history had it (what ?debug=lag draws).
    std::span<const declared_event> declared_events() const override { return judged_; }
    // The highest score; a tie at the top is nobody's win.
    uint32_t winner() const override;
    // Its bodies and its keys; its scoreboard and events are the protocol's own PlayerLine and
    // GameEvent kinds.
    protocol::game_manifest manifest() const override;

    const asteroids_params& params() const { return params_; }
    // Rock size of body `id`: 3 large, 2 medium, 1 small, 0 not a rock.
    uint32_t rock_size(uint32_t id) const;
    const shot_record* shot_of(uint32_t body_id) const override;
    // The owner of bullet `id`, or 0 when it is not a live bullet.
    uint32_t bullet_owner(uint32_t id) const;
    // True while `player`'s ship passes through everything after a respawn.
    bool invulnerable(const world::world& w, uint32_t player) const;
    uint32_t wave() const { return wave_size_; }

private:
    using ship_state = player_state;
    struct player {
        uint32_t ship = 0;       // body id while playing, else 0
        uint32_t last_ship = 0;  // the latest ship's id: the match names a leaving player by it
        ship_state state = ship_state::playing;
        uint32_t lives = 0;
        uint32_t respawn_at = 0;     // world tick of the respawn while respawning
        uint32_t vulnerable_at = 0;  // world tick from which it collides again
        uint32_t next_fire = 0;      // world tick from which it may fire
        score_line score;
    };
    struct bullet {
        uint32_t owner = 0;
        uint32_t expires = 0;  // world tick at which it is removed
        // For the wire (shot_of) only: it decides nothing in the game, so hash() leaves it out
        // and recordings keep their hashes.
        shot_record spawned;
        // Lag compensation (docs/LAG_COMPENSATION.md): how far in the past (1/256 ticks) its
        // shooter saw the world when firing, 0 = the present. A rewound bullet passes through
        // the present and hits the targets where they were that long before each tick.
        uint16_t rewind = 0;
        world::vec2 last_position{0, 0};  // before the last step: where its sweep starts
    };

    void make_ship(world::world& w, uint32_t player_id, player& p, uint32_t body_id, bool invulnerable);
    void fire(world::world& w, uint32_t player_id, player& p, uint16_t rewind);
    // The targets a bullet can hit now (vulnerable ships and rocks), into the history.
    void record_targets(const world::world& w);
    // Each rewound bullet's sweep of the last step against the targets as its shooter saw them:
    // the target the sweep reaches first is hit (`hit(bullet, target)`, the target rewound).
    template <class Hit>
    void judge_rewound(const world::world& w, Hit&& hit);
    // `shooter`: the player whose bullet did it, 0 for a rock.
    void destroy_ship(world::world& w, uint32_t player_id, uint32_t shooter, std::vector<uint32_t>& removals);
    void split_rock(world::world& w, uint32_t id, std::vector<uint32_t>& removals);
    void respawn_due(world::world& w);
    void spawn_wave(world::world& w);
    // A spot at least `clearance` beyond every body's edge (a few tries; the last otherwise).
    world::vec2 free_spot(const world::world& w, world::real radius, world::real clearance);
    player* player_of_ship(uint32_t body_id);

    asteroids_params params_;
    world::rng rng_;
    std::map<uint32_t, player> players_;  // by player id
    std::map<uint32_t, bullet> bullets_;  // by body id
    std::map<uint32_t, uint32_t> rocks_;  // body id → size
    uint32_t wave_size_ = 0;              // large rocks in the last wave
    hit_history history_;                 // the targets' recent past (derived: not hashed)
    std::vector<game_event> events_;      // the last after_step's
    std::vector<declared_event> judged_;  // the last after_step's hits judged in the past
};

}  // namespace arena::rules
