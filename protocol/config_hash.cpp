#include "protocol/config_hash.hpp"

#include "server/world/fnv1a.hpp"

namespace arena::protocol {

std::uint64_t world_config_hash(std::string_view world_config) noexcept {
    world::fnv1a_64 h;
    h.add_bytes(world_config);
    return h.value();
}

}  // namespace arena::protocol
