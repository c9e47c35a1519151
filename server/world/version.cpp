#include "server/world/version.hpp"

#include <algorithm>

namespace arena::world {

std::string changed_since(uint32_t recorded, const world_config& config) {
    const bool has_chain = std::any_of(config.bodies.begin(), config.bodies.end(),
                                       [](const body_config& b) { return b.shape.type == shape_type::chain; });
    if (recorded < 3 && has_chain)
        return "chains (version 3: their segments know their neighbours and collide on one side)";
    if (recorded < 4 && config.substeps > 1)
        return "sub-steps (version 4: the sub-stepped solver solves contacts colour by colour)";
    return {};
}

}  // namespace arena::world
