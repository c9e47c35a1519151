#include "server/match/match.hpp"

#include "protocol/config_hash.hpp"
#include "protocol/version.hpp"
#include "server/config/config_json.hpp"
#include "server/match/logger.hpp"

namespace arena::match {

using protocol::RejectCode;

match::match(const match_config& config, const world::world_config& world_config, logger log)
    : config_(config),
      log_(std::move(log)),
      world_(world_config, config.seed),
      world_config_json_(config::config_to_json(world_config)),
      world_config_hash_(protocol::world_config_hash(world_config_json_)),
      fanout_({config.view_radius, baseline_ring(), config.tick_rate}) {}

uint32_t match::snapshot_interval() const {
    return std::max<uint32_t>(1, config_.tick_rate / std::max<uint16_t>(1, config_.snapshot_rate));
}

uint32_t match::input_limit() const {
    return config_.max_inputs_per_second ? config_.max_inputs_per_second : 2u * config_.tick_rate + 10u;
}

std::variant<uint32_t, rejection> match::join(connection& who, const protocol::hello_msg& hello,
                                              const std::string& identity) {
    if (hello.protocol_version != protocol::protocol_version)
        return rejection{RejectCode::version_mismatch, "protocol version " + std::to_string(hello.protocol_version) +
                                                           " is not supported; this server speaks " +
                                                           std::to_string(protocol::protocol_version)};
    if (hello.name.size() > config_.max_name_bytes)
        return rejection{RejectCode::bad_request,
                         "name longer than " + std::to_string(config_.max_name_bytes) + " bytes"};
    if (hello.token.size() > config_.max_token_bytes)
        return rejection{RejectCode::bad_request,
                         "token longer than " + std::to_string(config_.max_token_bytes) + " bytes"};
    if (!identity.empty()) {
        for (auto& [id, p] : players_) {
            if (p.identity != identity) continue;
            // The same player again: a reconnection, or a new connection taking over.
            if (p.who) {
                connection* old = p.who;
                p.who = nullptr;  // detach first: the old connection's leave must not touch the player
                old->close_with_bye("signed in from another connection");
                ++counters_.takeovers;
            } else {
                ++counters_.reconnects;
            }
            p.who = &who;
            p.inputs = input_buffer(config_.input_buffer);
            p.last_received_sequence = 0;  // a new connection numbers its inputs from 1 again
            p.snapshots = snapshot_client(baseline_ring(), hello.delta_snapshots);  // holds no baseline yet
            if (p.body_id != 0) pending_welcomes_.push_back(id);
            log_("reconnect player=%u body=%u name=%s", id, p.body_id, p.name.c_str());
            return id;
        }
    }
    if (players_.size() >= config_.max_players)
        return rejection{RejectCode::server_full, "server full (" + std::to_string(config_.max_players) + " players)"};
    const uint32_t id = next_player_id_++;
    player p{&who, hello.name, identity,
             0,    0,          input_buffer(config_.input_buffer),
             0,    0,          snapshot_client(baseline_ring(), hello.delta_snapshots)};
    players_.emplace(id, std::move(p));
    pending_joins_.push_back(id);
    return id;
}

void match::leave(uint32_t player_id, const connection& who, std::string_view reason, bool connection_lost) {
    auto it = players_.find(player_id);
    if (it == players_.end() || it->second.who != &who) return;
    player& p = it->second;
    if (connection_lost && !p.identity.empty() && p.body_id != 0 && config_.reconnect_grace_s > 0) {
        p.who = nullptr;
        p.disconnected_at_tick = world_.tick();
        log_("disconnect player=%u name=%s reason=%.*s (body kept for %.0f s)", player_id, p.name.c_str(),
             static_cast<int>(reason.size()), reason.data(), config_.reconnect_grace_s);
        return;
    }
    remove_player(it, reason);
}

void match::remove_player(std::map<uint32_t, player>::iterator it, std::string_view reason) {
    player& p = it->second;
    if (p.body_id != 0) {
        pending_leaves_.push_back(p.body_id);
    } else {
        std::erase(pending_joins_, it->first);
    }
    std::erase(pending_welcomes_, it->first);
    counters_.input_underruns += p.inputs.underruns();
    counters_.input_overflows += p.inputs.overflows();
    ++counters_.leaves;
    log_("leave player=%u name=%s reason=%.*s", it->first, p.name.c_str(), static_cast<int>(reason.size()),
         reason.data());
    players_.erase(it);
}

void match::expire_disconnected() {
    const auto grace_ticks = static_cast<uint32_t>(config_.reconnect_grace_s * config_.tick_rate);
    for (auto it = players_.begin(); it != players_.end();) {
        auto next = std::next(it);
        if (!it->second.who && world_.tick() - it->second.disconnected_at_tick >= grace_ticks)
            remove_player(it, "reconnect grace period over");
        it = next;
    }
}

std::optional<rejection> match::receive_input(uint32_t player_id, const protocol::input_msg& input) {
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
    p.snapshots.acked_tick = input.snapshot_ack;
    p.inputs.push({input.sequence, in});
    return std::nullopt;
}

void match::tick() {
    expire_disconnected();
    tick_record record;
    record.tick = world_.tick();
    record.joins = pending_joins_;
    record.leaves = pending_leaves_;
    pending_joins_.clear();
    pending_leaves_.clear();
    for (auto& [id, p] : players_) {
        // A disconnected player's body coasts: no thrust, no turn, no buttons.
        if (p.body_id != 0) record.inputs.push_back({p.body_id, p.who ? p.inputs.consume() : world::player_input{}});
    }
    const std::vector<uint32_t> spawned = apply_tick(world_, record);
    if (on_tick) on_tick(record, world_.hash());
    spawn_pending(record.joins, spawned);
    for (uint32_t id : pending_welcomes_) {
        auto it = players_.find(id);
        if (it != players_.end() && it->second.who) send_welcome(id, it->second);
    }
    pending_welcomes_.clear();

    // The input rate is counted per second of ticks.
    if (world_.tick() % config_.tick_rate == 0) {
        for (auto& [id, p] : players_) p.inputs_this_window = 0;
    }
    send_snapshots();
}

void match::spawn_pending(const std::vector<uint32_t>& owners, const std::vector<uint32_t>& bodies) {
    for (size_t i = 0; i < owners.size(); ++i) {
        auto it = players_.find(owners[i]);
        if (it == players_.end()) continue;
        player& p = it->second;
        if (bodies[i] == 0) {
            if (p.who) p.who->close(RejectCode::server_full, "the world has no room for another body");
            continue;
        }
        p.body_id = bodies[i];
        ++counters_.joins;
        counters_.players_peak = std::max<uint32_t>(counters_.players_peak, static_cast<uint32_t>(players_.size()));
        if (p.who) send_welcome(owners[i], p);
        log_("join player=%u body=%u name=%s", owners[i], p.body_id, p.name.c_str());
    }
}

void match::send_welcome(uint32_t player_id, const player& p) {
    protocol::welcome_info welcome;
    welcome.player_id = player_id;
    welcome.entity_id = p.body_id;
    welcome.tick = world_.tick();
    welcome.tick_rate = config_.tick_rate;
    welcome.snapshot_rate = config_.snapshot_rate;
    welcome.preset = config_.preset;
    welcome.world_config = world_config_json_;
    welcome.world_config_hash = world_config_hash_;
    welcome.world_version = world::world_version;
    welcome.view_radius = config_.view_radius;
    p.who->send(protocol::encode_welcome(welcome));
}

void match::send_snapshots() {
    // BodyState clients all get theirs on the ticks that are multiples of the interval (one
    // shared frame when they see the whole world). Delta clients cost a view query and an
    // encoding each, so they are spread over the interval by player id: a third of them on
    // each tick at 60 Hz ticks and 20 Hz snapshots, not all of them on one tick.
    const uint32_t interval = snapshot_interval();
    const uint32_t phase = world_.tick() % interval;
    fanout_.begin(world_);
    for (auto& [id, p] : players_) {
        if (p.body_id == 0 || !p.who) continue;
        if ((p.snapshots.delta ? id % interval : 0) != phase) continue;
        const uint32_t ack = p.inputs.last_consumed_sequence();
        ++counters_.snapshots_sent;
        if (!p.snapshots.delta && fanout_.shared_full_frame()) {
            const protocol::snapshot_encoder& shared = fanout_.shared_frame();
            counters_.snapshot_bytes = shared.frame().size();
            p.who->send_snapshot(shared, ack);  // one memcpy, the ack patched in
            continue;
        }
        const auto frame =
            p.snapshots.delta ? fanout_.delta_frame(p.snapshots, p.body_id, ack) : fanout_.full_frame(p.body_id, ack);
        counters_.snapshot_bytes = frame.size();
        p.who->send_snapshot_frame(frame);
    }
}

match_counters match::counters() const {
    match_counters total = counters_;
    total.snapshots = fanout_.counters();
    for (const auto& [id, p] : players_) {
        total.input_underruns += p.inputs.underruns();
        total.input_overflows += p.inputs.overflows();
    }
    return total;
}

}  // namespace arena::match
