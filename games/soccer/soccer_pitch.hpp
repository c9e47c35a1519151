#pragma once
// Soccer's scene: a pitch seen from above, as Haxball draws it. Walls and goals are one closed
// chain of static segments; the ball is the one moving body the scene places; players spawn
// as the world spawns them and the rules put them in their half.
#include "server/world/config.hpp"

namespace arena::rules {

// Where things are on the pitch, m. The pitch is [left, right] × [bottom, top]; each goal is a
// pocket `goal_depth` deep behind its line, `goal_half_width` either side of the centre line.
struct pitch_geometry {
    world::real left = 4, right = 44, bottom = 4, top = 24;
    world::real goal_half_width = 3, goal_depth = 2;
    world::real corner_cut = 3;  // each corner is cut at 45°, this far along both lines
    world::real ball_radius = 0.5f;

    world::vec2 centre() const { return {(left + right) / 2, (bottom + top) / 2}; }
    world::real length() const { return right - left; }
};

inline constexpr pitch_geometry pitch{};

// The pitch: no gravity in the plane, air drag on the ball and the players, walls and goals,
// the ball on the centre spot. Rules: "soccer".
world::world_config soccer_pitch();

}  // namespace arena::rules
