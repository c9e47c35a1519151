#include "server/net/game.hpp"

#include "protocol/config_hash.hpp"
#include "protocol/version.hpp"
#include "server/config/config_json.hpp"
#include "server/net/log.hpp"

namespace arena::net {

using protocol::RejectCode;

game::game(const game_config& config, const world::world_config& world_config)
    : config_(config),
      world_(world_config, config.seed),
      world_config_json_(config::config_to_json(world_config)),
      world_config_hash_(protocol::world_config_hash(world_config_json_)) {}

uint32_t game::input_limit() const {
    return config_.max_inputs_per_second ? config_.max_inputs_per_second : 2u * config_.tick_rate + 10u;
}

std::variant<uint32_t, rejection> game::join(participant& who, const protocol::hello_msg& hello) {
    if (hello.protocol_version != protocol::protocol_version)
        return rejection{RejectCode::version_mismatch, "protocol version " + std::to_string(hello.protocol_version) +
                                                           " is not supported; this server speaks " +
                                                           std::to_string(protocol::protocol_version)};
    if (hello.name.size() > config_.max_name_bytes)
        return rejection{RejectCode::bad_request, "name longer than " + std::to_string(config_.max_name_bytes) + " bytes"};
    if (hello.token.size() > config_.max_token_bytes)
        return rejection{RejectCode::bad_request, "token longer than " + std::to_string(config_.max_token_bytes) + " bytes"};
    if (players_.size() >= config_.max_players)
        return rejection{RejectCode::server_full, "server full (" + std::to_string(config_.max_players) + " players)"};
    const uint32_t id = next_player_id_++;
    players_.emplace(id, player{&who, hello.name, 0, input_buffer(config_.input_buffer), 0, 0});
    pending_joins_.push_back(id);
    return id;
}

void game::leave(uint32_t player_id, std::string_view reason) {
    auto it = players_.find(player_id);
    if (it == players_.end()) return;
    player& p = it->second;
    if (p.body_id != 0) {
        pending_leaves_.push_back(p.body_id);
    } else {
        std::erase(pending_joins_, player_id);
    }
    counters_.input_underruns += p.inputs.underruns();
    counters_.input_overflows += p.inputs.overflows();
    ++counters_.leaves;
    log_line("leave player=%u name=%s reason=%.*s", player_id, p.name.c_str(), static_cast<int>(reason.size()),
             reason.data());
    players_.erase(it);
}

std::optional<rejection> game::receive_input(uint32_t player_id, const protocol::input_msg& input) {
    auto it = players_.find(player_id);
    if (it == players_.end()) return std::nullopt;
    player& p = it->second;
    ++counters_.inputs_received;
    if (++p.inputs_this_window > input_limit())
        return rejection{RejectCode::rate_limit, "more than " + std::to_string(input_limit()) + " inputs per second"};
    const world::player_input in{input.thrust, input.turn, input.buttons};
    if (auto problem = world::check_input(in)) return rejection{RejectCode::bad_input, *problem};
    if (input.sequence <= p.last_received_sequence) {
        ++counters_.stale_inputs;
        return std::nullopt;
    }
    p.last_received_sequence = input.sequence;
    p.inputs.push({input.sequence, in});
    return std::nullopt;
}

void game::tick() {
    replay::tick_record record;
    record.tick = world_.tick();
    record.joins = pending_joins_;
    record.leaves = pending_leaves_;
    pending_joins_.clear();
    pending_leaves_.clear();
    for (auto& [id, p] : players_) {
        if (p.body_id != 0) record.inputs.push_back({p.body_id, p.inputs.consume()});
    }
    const std::vector<uint32_t> spawned = replay::apply_tick(world_, record);
    if (on_tick) on_tick(record, world_.hash());
    spawn_pending(record.joins, spawned);

    // The input rate is counted per second of ticks.
    if (world_.tick() % config_.tick_rate == 0) {
        for (auto& [id, p] : players_) p.inputs_this_window = 0;
    }
    const uint32_t interval = std::max<uint32_t>(1, config_.tick_rate / std::max<uint16_t>(1, config_.snapshot_rate));
    if (world_.tick() % interval == 0) broadcast_snapshot();
}

void game::spawn_pending(const std::vector<uint32_t>& owners, const std::vector<uint32_t>& bodies) {
    for (size_t i = 0; i < owners.size(); ++i) {
        auto it = players_.find(owners[i]);
        if (it == players_.end()) continue;
        player& p = it->second;
        if (bodies[i] == 0) {
            p.who->reject(RejectCode::server_full, "the world has no room for another body");
            continue;
        }
        p.body_id = bodies[i];
        ++counters_.joins;
        counters_.players_peak = std::max<uint32_t>(counters_.players_peak, static_cast<uint32_t>(players_.size()));
        protocol::welcome_info welcome;
        welcome.player_id = owners[i];
        welcome.entity_id = p.body_id;
        welcome.tick = world_.tick();
        welcome.tick_rate = config_.tick_rate;
        welcome.snapshot_rate = config_.snapshot_rate;
        welcome.preset = config_.preset;
        welcome.world_config = world_config_json_;
        welcome.world_config_hash = world_config_hash_;
        welcome.world_version = world::world_version;
        p.who->send(protocol::encode_welcome(welcome));
        log_line("join player=%u body=%u name=%s", owners[i], p.body_id, p.name.c_str());
    }
}

void game::broadcast_snapshot() {
    // The shared part is built once; each client's copy differs only in its ack.
    body_states_.clear();
    for (const world::body& b : world_.bodies()) {
        body_states_.emplace_back(b.id, b.owner, b.position.x(), b.position.y(), b.velocity.x(), b.velocity.y(), b.angle,
                                  b.angular_velocity);
    }
    snapshot_.build(world_.tick(), body_states_);
    for (auto& [id, p] : players_) {
        if (p.body_id == 0) continue;
        p.who->send_snapshot(snapshot_, p.inputs.last_consumed_sequence());
        ++counters_.snapshots_sent;
    }
}

game_counters game::counters() const {
    game_counters total = counters_;
    for (const auto& [id, p] : players_) {
        total.input_underruns += p.inputs.underruns();
        total.input_overflows += p.inputs.overflows();
    }
    return total;
}

}  // namespace arena::net
