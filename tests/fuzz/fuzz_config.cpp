// Fuzz target: the world config loader (JSON text from a file or a Welcome).
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <variant>

#include "server/config/config_json.hpp"
#include "server/world/world.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace arena;
    auto parsed = config::parse_config_json(std::string_view(reinterpret_cast<const char*>(data), size));
    if (const world::world_config* c = parsed.ok() ? &parsed.value : nullptr) {
        // A config that loads must also build a world and step it; keep the fuzzer fast.
        if (c->rocks.count <= 64 && c->size.x() * c->size.y() < 1e8f) {
            world::world w(*c, 1);
            w.spawn_player(world::player_id{1});
            w.step({});
        }
        (void)config::parse_config_json(config::config_to_json(*c));
    }
    return 0;
}
