#include "scenes/scatter.hpp"

namespace arena::scenes {

world::body scattered_circle(world::rng& r, const scatter_box& box, world::body_material material) {
    // One draw per statement: argument evaluation order differs between compilers.
    material.radius = r.uniform(box.min_radius, box.max_radius);
    const world::real x = r.uniform(box.lo.x(), box.hi.x());
    const world::real y = r.uniform(box.lo.y(), box.hi.y());
    return world::make_body(material, {x, y});
}

}  // namespace arena::scenes
