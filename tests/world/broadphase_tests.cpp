// The grid broadphase finds exactly the overlapping pairs a brute-force scan finds.
#include <algorithm>
#include <catch2/catch.hpp>
#include <set>

#include "server/world/broadphase.hpp"
#include "server/world/rng.hpp"
#include "server/world/world.hpp"

using namespace arena::world;

namespace {

std::set<std::pair<uint32_t, uint32_t>> brute_force_overlaps(std::span<const body> bodies, const world_config& c) {
    std::set<std::pair<uint32_t, uint32_t>> out;
    for (uint32_t i = 0; i < bodies.size(); ++i)
        for (uint32_t j = i + 1; j < bodies.size(); ++j) {
            const real reach = bodies[i].radius + bodies[j].radius;
            if (displacement(bodies[i].position, bodies[j].position, c).squaredNorm() < reach * reach) out.insert({i, j});
        }
    return out;
}

}  // namespace

TEST_CASE("grid pairs match brute force in open, wrapping and walled worlds", "[world][broadphase]") {
    for (boundary mode : {boundary::open, boundary::wrap, boundary::walls}) {
        for (uint64_t seed = 1; seed <= 20; ++seed) {
            world_config c;
            c.boundary = mode;
            c.size = {60, 40};
            rng r(seed);
            std::vector<body> bodies;
            const int n = 50 + static_cast<int>(seed) * 7;
            for (int i = 0; i < n; ++i) {
                body_material m;
                m.radius = r.uniform(0.2f, 2.0f);
                const real x = r.uniform(0, 60);
                const real y = r.uniform(0, 40);
                bodies.push_back(make_body(m, {x, y}));
            }
            broadphase_scratch scratch;
            find_candidate_pairs(bodies, c, scratch);
            std::set<std::pair<uint32_t, uint32_t>> found;
            for (auto [a, b] : scratch.pairs) {
                REQUIRE(a < b);
                REQUIRE(found.insert({a, b}).second);  // each pair once
            }
            for (const auto& pair : brute_force_overlaps(bodies, c)) {
                INFO("mode " << static_cast<int>(mode) << " seed " << seed);
                CHECK(found.count(pair) == 1);
            }
        }
    }
}
