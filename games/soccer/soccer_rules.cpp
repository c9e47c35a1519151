#include "games/soccer/soccer_rules.hpp"

#include <algorithm>
#include <cmath>

#include "games/soccer/soccer_pitch.hpp"
#include "server/world/trig.hpp"

namespace arena::rules {

using world::real;
using world::vec2;

namespace {

// Kick-off spots: a team's players in a column a quarter of the pitch from the centre line, the
// first on the line through the goals, the next ones `spacing` above and below it in turn; a full
// column (five on the default pitch) starts another one `spacing` further back.
constexpr real spacing = 3.0f;

}  // namespace

soccer_rules::soccer_rules(world::world& w, const soccer_params& params) : params_(params) {
    for (const world::body& b : w.bodies()) {
        if (!b.is_static() && b.owner == 0) {
            ball_ = b.id;
            break;
        }
    }
    const double ticks = std::ceil(static_cast<double>(params_.match_seconds) / static_cast<double>(w.config().dt));
    start_tick_ = w.tick();
    final_tick_ = w.tick() + static_cast<uint32_t>(std::min(ticks, 4.0e9));
    w.set_contact_events(true);
}

void soccer_rules::on_joins(world::world& w, std::span<const uint32_t> owners, std::span<const uint32_t> bodies) {
    for (size_t k = 0; k < owners.size() && k < bodies.size(); ++k) {
        if (bodies[k] == 0) continue;
        size_t reds = 0, blues = 0;
        for (const auto& [id, p] : players_) (p.team == team_red ? reds : blues) += 1;
        player& p = players_[owners[k]];
        p.body = bodies[k];
        p.team = reds <= blues ? team_red : team_blue;
        place_in_half(w, owners[k], p);
    }
}

void soccer_rules::on_leaves(world::world&, std::span<const uint32_t> bodies) {
    for (const uint32_t body : bodies) {
        const uint32_t id = player_of_body(body);
        if (id == 0) continue;
        if (last_touch_ == id) last_touch_ = 0;
        players_.erase(id);
    }
}

void soccer_rules::before_step(world::world& w, const world::tick_inputs& inputs) {
    events_.clear();  // here, not in after_step: a kick-off happens before the step
    if (finished_) return;
    if (kickoff_at_ != 0 && w.tick() >= kickoff_at_) kick_off(w);
    // In body id order, whatever order the inputs come in: two players kicking in one tick
    // kick in the same order everywhere.
    std::vector<std::pair<uint32_t, uint32_t>> kickers;  // (body, player)
    for (const world::body_input& in : inputs) {
        if ((in.input.buttons & soccer_button_kick) == 0) continue;
        if (const uint32_t id = player_of_body(in.body_id.value()); id != 0)
            kickers.emplace_back(in.body_id.value(), id);
    }
    std::sort(kickers.begin(), kickers.end());
    for (const auto& [body, id] : kickers) kick(w, id, players_.at(id));
    roll_ball(w);
}

void soccer_rules::kick(world::world& w, uint32_t player_id, player& p) {
    if (w.tick() < p.next_kick) return;
    world::body* ball = w.find(ball_);
    const world::body* kicker = w.find(p.body);
    if (ball == nullptr || kicker == nullptr) return;
    const vec2 offset = ball->position - kicker->position;
    const real distance = offset.norm();
    if (distance > kicker->radius + ball->radius + params_.kick_reach || distance == 0) return;
    // The lecture's impulse: Δv = J/m along the line of centres, at once.
    ball->apply_impulse(offset * (params_.kick_impulse / distance));
    p.next_kick = w.tick() + params_.kick_cooldown_ticks;
    p.kicks += 1;
    last_touch_ = player_id;
}

void soccer_rules::roll_ball(world::world& w) const {
    world::body* ball = w.find(ball_);
    if (ball == nullptr) return;
    const real speed = ball->velocity.norm();
    if (speed == 0) return;
    // Kinetic friction μ·N with N = m·g, against the motion: as resistance, so the world's
    // integration stops the ball rather than reversing it.
    ball->resistance -= ball->velocity * (params_.ball_friction * ball->mass * params_.gravity / speed);
}

void soccer_rules::after_step(world::world& w) {
    if (finished_) return;
    for (const world::contact_event& e : w.contact_events()) {
        if (e.a != ball_ && e.b != ball_) continue;
        if (const uint32_t id = player_of_body(e.a == ball_ ? e.b : e.a); id != 0) last_touch_ = id;
    }
    if (kickoff_at_ == 0) check_goal(w);
    if (w.tick() >= final_tick_) {
        finished_ = true;
        events_.push_back({static_cast<uint8_t>(soccer_event::full_time), {winning_team()}});
    } else if (w.tick() >= period_end_tick()) {
        // The next period starts with a kick-off, like play after a goal.
        events_.push_back({static_cast<uint8_t>(soccer_event::period_end), {static_cast<int32_t>(period_)}});
        period_ += 1;
        kickoff_at_ = w.tick() + std::max<uint32_t>(params_.kickoff_ticks, 1);
    }
}

uint32_t soccer_rules::period_end_tick() const {
    // Whole ticks, the last period ending exactly with the clock.
    const uint64_t length = final_tick_ - start_tick_;
    return start_tick_ + static_cast<uint32_t>(length * period_ / params_.periods);
}

void soccer_rules::check_goal(world::world& w) {
    const world::body* ball = w.find(ball_);
    if (ball == nullptr) return;
    // Wholly past the line: red attacks the right goal, blue the left one.
    uint8_t scorers = 0;
    if (ball->position.x() > pitch.right + ball->radius) scorers = team_red;
    if (ball->position.x() < pitch.left - ball->radius) scorers = team_blue;
    if (scorers == 0) return;
    (scorers == team_red ? goals_red_ : goals_blue_) += 1;
    const auto it = players_.find(last_touch_);
    const bool own_goal = it != players_.end() && it->second.team != scorers;
    if (it != players_.end() && !own_goal) it->second.goals += 1;
    events_.push_back({static_cast<uint8_t>(own_goal ? soccer_event::own_goal : soccer_event::goal),
                       {static_cast<int32_t>(last_touch_), scorers}});
    kickoff_at_ = w.tick() + std::max<uint32_t>(params_.kickoff_ticks, 1);
}

void soccer_rules::kick_off(world::world& w) {
    kickoff_at_ = 0;
    last_touch_ = 0;
    events_.push_back({static_cast<uint8_t>(soccer_event::kickoff), {}});
    if (world::body* ball = w.find(ball_)) {
        ball->position = pitch.centre();
        ball->velocity = {0, 0};
        ball->angular_velocity = 0;
    }
    for (const auto& [id, p] : players_) place_in_half(w, id, p);
}

void soccer_rules::place_in_half(world::world& w, uint32_t player_id, const player& p) const {
    world::body* b = w.find(p.body);
    if (b == nullptr) return;
    // Its place among its team's players, by player id.
    uint32_t index = 0;
    for (const auto& [id, other] : players_)
        if (other.team == p.team && id < player_id) ++index;
    const auto reach = static_cast<uint32_t>(((pitch.top - pitch.bottom) / 2 - b->radius - 0.5f) / spacing);
    const uint32_t rows = 2 * reach + 1;
    const uint32_t row = index % rows, column = index / rows;
    // Row 0 on the line, 1 above, 2 below, 3 further above...
    const real across = spacing * static_cast<real>((row + 1) / 2) * (row % 2 == 1 ? 1.0f : -1.0f);
    const real side = p.team == team_red ? -1.0f : 1.0f;
    const real x = pitch.centre().x() + side * (pitch.length() / 4 + spacing * static_cast<real>(column));
    const real y = pitch.centre().y() + across;
    b->position = {std::clamp(x, pitch.left + b->radius, pitch.right - b->radius), y};
    b->velocity = {0, 0};
    b->angular_velocity = 0;
    b->angle = p.team == team_red ? 0.0f : world::pi;
}

uint32_t soccer_rules::player_of_body(uint32_t body_id) const {
    for (const auto& [id, p] : players_)
        if (p.body == body_id) return id;
    return 0;
}

uint8_t soccer_rules::kind_of(uint32_t body_id) const {
    if (body_id == ball_) return kind_ball;
    return player_of_body(body_id) != 0 ? kind_player : 0;
}

void soccer_rules::hash(world::fnv1a& h) const {
    h.add_u32(ball_);
    h.add_u32(final_tick_);
    h.add_u32(goals_red_);
    h.add_u32(goals_blue_);
    h.add_u32(last_touch_);
    h.add_u32(kickoff_at_);
    h.add_u8(finished_ ? 1 : 0);
    h.add_u32(start_tick_);
    h.add_u32(period_);
    h.add_u32(static_cast<uint32_t>(players_.size()));
    for (const auto& [id, p] : players_) {
        h.add_u32(id);
        h.add_u32(p.body);
        h.add_u8(p.team);
        h.add_u32(p.goals);
        h.add_u32(p.kicks);
        h.add_u32(p.next_kick);
    }
}

std::vector<score_line> soccer_rules::scoreboard() const {
    std::vector<score_line> board;
    board.reserve(players_.size());
    for (const auto& [id, p] : players_)
        board.push_back({.player = id,
                         .score = p.goals,
                         .shots = p.kicks,
                         .team = p.team,
                         .values = {p.team, static_cast<int32_t>(p.goals), static_cast<int32_t>(p.kicks)}});
    return board;
}

std::vector<team_line> soccer_rules::teams() const {
    return {{team_red, "red", goals_red_, {static_cast<int32_t>(goals_red_)}},
            {team_blue, "blue", goals_blue_, {static_cast<int32_t>(goals_blue_)}}};
}

std::vector<uint32_t> soccer_rules::winners() const {
    std::vector<uint32_t> out;
    const uint8_t team = winning_team();
    for (const auto& [id, p] : players_)
        if (team != 0 && p.team == team) out.push_back(id);
    return out;
}

protocol::game_manifest soccer_rules::manifest() const {
    using protocol::GameFieldKind;
    protocol::game_manifest m;
    m.name = "soccer";
    m.player_fields = {{"team", "Team", GameFieldKind::team},
                       {"goals", "Goals", GameFieldKind::count},
                       {"kicks", "Kicks", GameFieldKind::count}};
    m.team_fields = {{"goals", "Goals", GameFieldKind::count}};
    m.teams = {{"red", "#e04848"}, {"blue", "#4878e0"}};
    m.rank_field = "goals";
    // In soccer_event's order.
    m.events = {{"goal", {"player", "team"}, "{player} scores for {team}"},
                {"own_goal", {"player", "team"}, "own goal by {player}: a goal for {team}"},
                {"kickoff", {}, "kick-off"},
                {"full_time", {"team"}, "full time: {team}"},
                {"period_end", {"period"}, "end of period {period}"}};
    m.body_tags = {{kind_player, "player", "ship", "team"}, {kind_ball, "ball", "disc", "#ffffff"}};
    m.inputs = {{"kick", 1, "Space"}, {"dash", 0, "ShiftLeft"}};
    return m;
}

uint8_t soccer_rules::winning_team() const {
    if (goals_red_ == goals_blue_) return 0;
    return goals_red_ > goals_blue_ ? team_red : team_blue;
}

}  // namespace arena::rules
