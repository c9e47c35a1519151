// The grid broadphase finds exactly the overlapping pairs a brute-force scan finds.
#include <algorithm>
#include <catch2/catch.hpp>
#include <set>

#include "scenes/scatter.hpp"
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
            if (displacement(bodies[i].position, bodies[j].position, c).squaredNorm() < reach * reach)
                out.insert({i, j});
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
            for (int i = 0; i < n; ++i)
                bodies.push_back(arena::scenes::scattered_circle(r, {{0, 0}, {60, 40}, 0.2f, 2.0f}));
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

namespace {

// The pair order broadphase.hpp documents, built the slow way: bodies by (cell, index); each
// meets the later bodies of its own cell, then those of the cells (+1, 0), (−1, +1), (0, +1),
// (+1, +1), each cell in index order; a wrapping grid takes neighbours modulo its size, a
// closed one has none outside.
std::vector<std::pair<uint32_t, uint32_t>> pairs_in_documented_order(std::span<const body> bodies, const grid& g) {
    std::vector<uint32_t> cell(bodies.size());
    std::vector<uint32_t> order(bodies.size());
    for (uint32_t i = 0; i < bodies.size(); ++i) {
        cell[i] = cell_index(g, bodies[i].position);
        order[i] = i;
    }
    std::stable_sort(order.begin(), order.end(), [&](uint32_t l, uint32_t r) { return cell[l] < cell[r]; });
    std::vector<std::pair<uint32_t, uint32_t>> out;
    auto meet = [&](uint32_t i, uint32_t j) {
        out.emplace_back(std::min(i, j), std::max(i, j));
    };
    for (size_t k = 0; k < order.size(); ++k) {
        const uint32_t i = order[k];
        for (size_t l = k + 1; l < order.size() && cell[order[l]] == cell[i]; ++l) meet(i, order[l]);
        const int cx = static_cast<int>(cell[i] % g.stride), cy = static_cast<int>(cell[i] / g.stride);
        for (auto [dx, dy] : {std::pair{1, 0}, {-1, 1}, {0, 1}, {1, 1}}) {
            int x = cx + dx, y = cy + dy;
            const int nx = static_cast<int>(g.nx), ny = static_cast<int>(g.ny);
            if (x < 0 || x >= nx || y >= ny) {
                if (!g.wraps) continue;
                x = (x + nx) % nx;
                y %= ny;
            }
            const uint32_t neighbour = static_cast<uint32_t>(y) * g.stride + static_cast<uint32_t>(x);
            for (uint32_t j : order)
                if (cell[j] == neighbour) meet(i, j);
        }
    }
    return out;
}

}  // namespace

// The contact list, and so the solver's results, follow this order: every path of the walk (a
// closed grid's table, a wrapping grid's table, a sparse wrapping grid's runs) must keep it.
TEST_CASE("candidate pairs come in the documented order on every path", "[world][broadphase]") {
    struct scene {
        boundary mode;
        vec2 size;
        real spread;  // bodies within ±spread/2 of the origin corner (wrapping across it)
    };
    const scene scenes[] = {
        {boundary::open, {60, 40}, 40},
        {boundary::walls, {60, 40}, 40},
        {boundary::wrap, {60, 40}, 60},      // a small wrapping grid: it gets the table
        {boundary::wrap, {3000, 3000}, 80},  // 746² cells: too many for a table, the runs
    };
    for (const scene& sc : scenes) {
        for (uint64_t seed = 1; seed <= 10; ++seed) {
            world_config c;
            c.boundary = sc.mode;
            c.size = sc.size;
            rng r(seed);
            std::vector<body> bodies;
            for (int i = 0; i < 150; ++i) {
                body_material m;
                m.radius = r.uniform(0.3f, 2.0f);
                vec2 p{r.uniform(-sc.spread / 2, sc.spread / 2), r.uniform(-sc.spread / 2, sc.spread / 2)};
                if (sc.mode == boundary::wrap) {
                    p = {p.x() < 0 ? p.x() + sc.size.x() : p.x(), p.y() < 0 ? p.y() + sc.size.y() : p.y()};
                }
                bodies.push_back(make_body(m, p));
            }
            const grid g = make_grid(bodies, c);
            broadphase_scratch scratch;
            find_candidate_pairs(bodies, g, scratch);
            INFO("mode " << static_cast<int>(sc.mode) << " size " << sc.size.x() << " seed " << seed);
            CHECK((scratch.cell_start.empty()) == (sc.size.x() == 3000));  // the path this scene meant
            CHECK(scratch.pairs == pairs_in_documented_order(bodies, g));
        }
    }
}
