#pragma once
// Circles scattered at random in a box: the scene of the broadphase and view-index property
// tests and of the integration benchmark. Every draw comes from the world's rng in a fixed
// order (radius, x, y), so a seed always gives the same scene.
#include "server/world/body.hpp"
#include "server/world/rng.hpp"

namespace arena::scenes {

// The box and the radii to draw from: radius in [min_radius, max_radius), position in [lo, hi).
struct scatter_box {
    world::vec2 lo{0, 0};
    world::vec2 hi{0, 0};
    world::real min_radius = 0;
    world::real max_radius = 0;
};

// One body of `material` (its radius drawn) at rest at a random place in the box.
world::body scattered_circle(world::rng& r, const scatter_box& box, world::body_material material = {});

}  // namespace arena::scenes
