#include "client_sim/client_shared.hpp"

#include <variant>

#include "server/config/config_json.hpp"

namespace arena::bots {

result<const world::world_config*> client_shared::config_for(const protocol::welcome_info& welcome) {
    using shared = result<const world::world_config*>;
    if (config_ && welcome.world_config == config_text_) return shared::success(&*config_);
    auto parsed = config::parse_config_json(welcome.world_config);
    if (!parsed) return shared::failure(std::move(parsed.error));
    config_ = std::move(parsed.value);
    config_text_ = welcome.world_config;
    return shared::success(&*config_);
}

void client_shared::on_joined(const protocol::welcome_info&) {
    ++playing_;
}

void client_shared::on_ended(bool was_playing) {
    ++ended_;
    if (was_playing) --playing_;
}

}  // namespace arena::bots
