#pragma once
// Soccer as Haxball plays it, on the lecture's physics:
// - Two teams, red (1) defending the left goal and blue (2) the right one; a player joins the
//   team with fewer players (red on a tie) and starts in its half.
// - Kick (Input.buttons bit 1): a ball within reach gets the impulse J along the line from the
//   kicker's centre to the ball's (Δv = J/m at once); a cooldown between kicks.
// - The ball rolls: the pitch's kinetic friction μ·m·g opposes its motion (it stops, never
//   reverses), on top of the world's air drag.
// - A ball wholly past a goal line is a goal for the other team, and for the last player who
//   touched it when that player attacks that goal (an own goal scores for the team only).
//   After kickoff_ticks, the kick-off: the ball on the centre spot at rest, every player back in
//   its half, facing the other goal.
// - The match clock: after match_seconds the match is over; the team with more goals wins, or
//   it is a draw. The clock runs in `periods` equal parts (two halves by default): the end of
//   each but the last is told as an event and followed by a kick-off (the teams keep their ends).
#include <cstdint>
#include <map>
#include <vector>

#include "games/soccer/soccer_params.hpp"
#include "server/rules/rules.hpp"

namespace arena::rules {

inline constexpr uint8_t soccer_button_kick = 1u << 1;
inline constexpr uint8_t team_red = 1;
inline constexpr uint8_t team_blue = 2;
// BodyShape.kind of the game's bodies: a player (drawn with its facing) and the ball.
inline constexpr uint8_t kind_player = 1;
inline constexpr uint8_t kind_ball = 4;
// Its events (manifest().events, in this order).
enum class soccer_event : uint8_t { goal, own_goal, kickoff, full_time, period_end };

class soccer_rules : public rules {
public:
    // The ball is the first moving body of `w` without an owner (soccer_pitch places it).
    explicit soccer_rules(world::world& w, const soccer_params& params = {});

    void on_joins(world::world& w, std::span<const uint32_t> owners, std::span<const uint32_t> bodies) override;
    void on_leaves(world::world& w, std::span<const uint32_t> bodies) override;
    void before_step(world::world& w, const world::tick_inputs& inputs) override;
    void after_step(world::world& w) override;

    uint8_t kind_of(uint32_t body_id) const override;
    // The ball matters most: every play is about it.
    uint8_t snapshot_weight(uint8_t kind) const override { return kind == kind_ball ? 4 : 3; }
    bool has_state() const override { return true; }
    void hash(world::fnv1a& h) const override;
    std::vector<score_line> scoreboard() const override;
    std::vector<team_line> teams() const override;
    uint8_t winning_team() const override;
    std::vector<uint32_t> winners() const override;
    bool finished() const override { return finished_; }
    // Team, goals and kicks a player; goals a team; goal, own goal, kick-off and full time;
    // the players drawn in their team's colour and the ball as a white disc; kick on Space.
    protocol::game_manifest manifest() const override;
    std::span<const declared_event> declared_events() const override { return events_; }

    uint32_t ball() const { return ball_; }
    uint32_t score(uint8_t team) const { return team == team_red ? goals_red_ : goals_blue_; }
    // The world tick at which the clock runs out.
    uint32_t final_tick() const { return final_tick_; }
    // The period being played, 1 to params().periods, and the world tick at which it ends.
    uint32_t period() const { return period_; }
    uint32_t period_end_tick() const;
    // True between a goal and its kick-off.
    bool awaiting_kickoff() const { return kickoff_at_ != 0; }
    const soccer_params& params() const { return params_; }

private:
    struct player {
        uint32_t body = 0;
        uint8_t team = 0;
        uint32_t goals = 0;
        uint32_t kicks = 0;
        uint32_t next_kick = 0;  // world tick from which it may kick
    };

    void kick(world::world& w, uint32_t player_id, player& p);
    void roll_ball(world::world& w) const;
    void check_goal(world::world& w);
    void kick_off(world::world& w);
    // Where player `id` of `team` stands at a kick-off, facing the other goal.
    void place_in_half(world::world& w, uint32_t player_id, const player& p) const;
    uint32_t player_of_body(uint32_t body_id) const;

    soccer_params params_;
    uint32_t ball_ = 0;
    uint32_t start_tick_ = 0;  // the clock starts
    uint32_t final_tick_ = 0;  // and runs out
    uint32_t period_ = 1;
    std::map<uint32_t, player> players_;  // by player id
    uint32_t goals_red_ = 0, goals_blue_ = 0;
    uint32_t last_touch_ = 0;  // player id, 0 = nobody since the kick-off
    uint32_t kickoff_at_ = 0;  // world tick of the next kick-off, 0 = none pending
    bool finished_ = false;
    std::vector<declared_event> events_;  // the last after_step's
};

}  // namespace arena::rules
