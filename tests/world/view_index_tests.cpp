// The view index finds exactly the bodies a scan of every body finds, in id order.
#include <catch2/catch.hpp>
#include <vector>

#include "scenes/scatter.hpp"
#include "server/world/rng.hpp"
#include "server/world/view_index.hpp"

using namespace arena::world;

namespace {

std::vector<uint32_t> brute_force_view(std::span<const body> bodies, const world_config& c, vec2 centre, real radius) {
    std::vector<uint32_t> out;
    for (uint32_t i = 0; i < bodies.size(); ++i) {
        const real limit = radius + bodies[i].radius;
        if (displacement(centre, bodies[i].position, c).squaredNorm() <= limit * limit) out.push_back(i);
    }
    return out;
}

}  // namespace

TEST_CASE("view queries match a scan of every body in open, wrapping and walled worlds", "[world][view]") {
    for (boundary mode : {boundary::open, boundary::wrap, boundary::walls}) {
        for (uint64_t seed = 1; seed <= 12; ++seed) {
            world_config c;
            c.boundary = mode;
            c.size = {200, 120};
            rng r(seed);
            std::vector<body> bodies;
            const int n = 100 + static_cast<int>(seed) * 40;
            // Open worlds let bodies stray outside the nominal size.
            const real spill = mode == boundary::open ? 30.0f : 0.0f;
            const arena::scenes::scatter_box box{{-spill, -spill}, {200 + spill, 120 + spill}, 0.2f, 3.0f};
            for (int i = 0; i < n; ++i) bodies.push_back(arena::scenes::scattered_circle(r, box));
            // Small radii, one near the cell size, and one wider than half the world (a wrap
            // then covers every cell).
            for (real radius : {1.0f, 15.0f, 40.0f, 130.0f}) {
                view_index index;
                index.build(bodies, c, radius);
                for (int q = 0; q < 25; ++q) {
                    const vec2 centre{r.uniform(-10, 210), r.uniform(-10, 130)};
                    std::vector<uint32_t> found;
                    index.query(centre, found);
                    INFO("mode " << static_cast<int>(mode) << " seed " << seed << " radius " << radius);
                    REQUIRE(found == brute_force_view(bodies, c, centre, radius));
                }
            }
        }
    }
}

TEST_CASE("a view query appends to what the caller already holds", "[world][view]") {
    world_config c;
    c.size = {100, 100};
    std::vector<body> bodies;
    body_material m;
    m.radius = 1;
    for (int i = 0; i < 10; ++i) bodies.push_back(make_body(m, {10.0f * static_cast<real>(i), 50}));
    view_index index;
    index.build(bodies, c, 15);
    std::vector<uint32_t> out{99};
    index.query({50, 50}, out);
    // Centres at 40, 50, 60 are within 15 + 1 m; 30 and 70 are 20 m away.
    CHECK(out == std::vector<uint32_t>{99, 4, 5, 6});
}
