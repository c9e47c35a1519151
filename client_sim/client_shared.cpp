#include "client_sim/client_shared.hpp"

#include <variant>

#include "server/config/config_json.hpp"

namespace arena::bots {

const world::world_config* client_shared::config_for(const protocol::welcome_info& welcome, std::string& error) {
    if (config_ && welcome.world_config == config_text_) return &*config_;
    auto parsed = config::parse_config_json(welcome.world_config);
    if (auto* e = std::get_if<config::config_error>(&parsed)) {
        error = e->message;
        return nullptr;
    }
    config_ = std::get<world::world_config>(std::move(parsed));
    config_text_ = welcome.world_config;
    return &*config_;
}

void client_shared::on_joined(const protocol::welcome_info&) {
    ++playing_;
}

void client_shared::on_ended(bool was_playing) {
    ++ended_;
    if (was_playing) --playing_;
}

}  // namespace arena::bots
