#pragma once
// Uniform-grid broadphase: candidate pairs of circles whose cells touch, in a deterministic
// order (cells in index order, bodies within a cell in id order).
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "server/world/body.hpp"
#include "server/world/config.hpp"

namespace arena::world {

// Buffers reused from step to step so that the broadphase allocates only while the world grows.
struct broadphase_scratch {
    std::vector<uint32_t> cell_of;      // body index → cell
    std::vector<uint32_t> cell_start;   // cell → first slot in `sorted` (size cells + 1)
    std::vector<uint32_t> sorted;       // body indices sorted by cell, stable
    std::vector<uint32_t> cursor;       // cell → next free slot while sorting
    std::vector<std::pair<uint32_t, uint32_t>> pairs;  // candidate (a, b) indices, a < b
};

// The uniform grid over the world: cells at least as wide as the largest circle's diameter.
struct grid {
    vec2 origin{0, 0};
    vec2 cell{1, 1};  // m, width and height of a cell
    uint32_t nx = 1;
    uint32_t ny = 1;
    bool wraps = false;
};

// The grid that covers `bodies` under `config`'s boundary.
grid make_grid(std::span<const body> bodies, const world_config& config);

// Fills scratch.pairs with candidate pairs of body indices (a < b), each pair once.
void find_candidate_pairs(std::span<const body> bodies, const world_config& config, broadphase_scratch& scratch);

// Displacement from a to b: the shortest one when the world wraps.
vec2 displacement(const vec2& a, const vec2& b, const world_config& config);

}  // namespace arena::world
