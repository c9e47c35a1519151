#include "games/soccer/soccer_bot.hpp"

#include <algorithm>
#include <cmath>

#include "games/soccer/soccer_pitch.hpp"
#include "games/soccer/soccer_rules.hpp"
#include "server/world/trig.hpp"

namespace arena::rules {

namespace {

using world::real;
using world::vec2;

constexpr real shooting_range = 14.0f;  // m from the goal: shoot rather than pass
constexpr real ahead_by = 4.0f;         // m nearer the goal than the ball: a team-mate worth a pass

class soccer_bot : public bots::game_bot {
public:
    world::player_input next(const bots::game_view& seen) override {
        if (seen.own == nullptr || seen.game == nullptr || seen.values == nullptr) return {};
        const int team_field = seen.game->player_field("team");
        const auto mine = seen.values->find(seen.player);
        if (team_field < 0 || mine == seen.values->end()) return {};
        const int32_t team = mine->second[static_cast<size_t>(team_field)];
        const real attack = team == team_red ? pitch.right : pitch.left;  // the goal line it attacks
        const real forward = team == team_red ? 1.0f : -1.0f;
        const protocol::BodyState* ball = nullptr;
        for (const protocol::BodyState& b : seen.bodies)
            if (seen.kind_of(b.id()) == kind_ball) ball = &b;
        if (ball == nullptr) return {};
        const vec2 at{ball->x(), ball->y()};
        // Its team-mates, and which of the team is nearest the ball.
        real my_distance = (at - seen.own->position).norm();
        bool nearest = true;
        uint32_t place = 0;                          // its rank by player id among its team: where it stands
        const protocol::BodyState* ahead = nullptr;  // the team-mate furthest towards the goal
        for (const protocol::BodyState& b : seen.bodies) {
            if (b.owner() == 0 || b.owner() == seen.player) continue;
            const auto values = seen.values->find(b.owner());
            if (values == seen.values->end() || values->second[static_cast<size_t>(team_field)] != team) continue;
            const vec2 p{b.x(), b.y()};
            if ((at - p).norm() < my_distance) nearest = false;
            if (b.owner() < seen.player) ++place;
            if (forward * (p.x() - at.x()) > ahead_by && (!ahead || forward * (b.x() - ahead->x()) > 0)) ahead = &b;
        }
        if (!nearest) return support(*seen.own, at, forward, place);
        // Shoot at the goal's centre, or pass to the team-mate ahead.
        const vec2 goal{attack, pitch.centre().y()};
        const vec2 target = ahead && (goal - at).norm() > shooting_range ? vec2{ahead->x(), ahead->y()} : goal;
        const real reach = seen.own->radius + pitch.ball_radius;
        // Behind the ball as seen from the target, but on the pitch: a ball on a wall is kicked
        // off it, along the line from the spot it can reach.
        const real margin = seen.own->radius + 0.1f;
        const vec2 wanted = at - (target - at).normalized() * reach;
        const vec2 behind{std::clamp(wanted.x(), pitch.left + margin, pitch.right - margin),
                          std::clamp(wanted.y(), pitch.bottom + margin, pitch.top - margin)};
        const vec2 aim = (at - behind).normalized();
        // Far from the spot: go round to it; near it: run through the ball.
        const bool placed = (behind - seen.own->position).norm() < 0.8f;
        world::player_input in = run_to(*seen.own, placed ? at : behind);
        // Kick when the ball is in reach and the line from its centre to the ball's points the way it should go.
        const vec2 to_ball = at - seen.own->position;
        if (to_ball.norm() < reach + 0.3f && to_ball.normalized().dot(aim) > 0.5f) in.buttons = soccer_button_kick;
        return in;
    }

private:
    // Not nearest the ball: the first stays back, between the ball and its own goal; the others
    // spread across the pitch ahead of the ball, ready for a pass.
    static world::player_input support(const world::body& own, const vec2& ball, real forward, uint32_t place) {
        if (place == 0)
            return run_to(own, {(ball.x() + (forward > 0 ? pitch.left : pitch.right)) / 2, pitch.centre().y()});
        const real across = place % 2 == 1 ? 5.0f : -5.0f;
        const real x = std::clamp(ball.x() + forward * 8.0f, pitch.left + 2, pitch.right - 2);
        return run_to(own, {x, std::clamp(ball.y() + across, pitch.bottom + 2, pitch.top - 2)});
    }
};

}  // namespace

world::player_input run_to(const world::body& own, const world::vec2& target) {
    const vec2 way = target - own.position;
    const world::cos_sin facing = world::compute_cos_sin(own.angle);
    const real cross = facing.c * way.y() - facing.s * way.x();
    const real dot = facing.c * way.x() + facing.s * way.y();
    world::player_input in;
    in.turn = std::clamp(cross, -1.0f, 1.0f);
    in.thrust = dot > 0 ? std::min(1.0f, way.norm() / 2) : 0.0f;
    return in;
}

std::unique_ptr<bots::game_bot> make_soccer_bot(std::uint64_t, std::uint32_t) {
    return std::make_unique<soccer_bot>();
}

}  // namespace arena::rules
