// Joining a match: a new connection, its Hello (a player, a reconnect, a takeover or a
// spectator), the reconnect grace, and the Welcome.
#include "server/match/match.hpp"

#include <algorithm>

#include "protocol/config_hash.hpp"
#include "protocol/version.hpp"
#include "server/config/config_json.hpp"
#include "server/match/logger.hpp"
#include "server/match/shape_wire.hpp"

namespace arena::match {

using protocol::RejectCode;

bool match::connect(connection& c) {
    client cl;
    cl.serial = next_serial_++;
    cl.address = std::string(c.address());
    cl.standing.connected_tick = world_.tick();
    auto [it, inserted] = clients_.emplace(&c, cl);
    if (!inserted) return true;  // already known: a transport bug, but harmless
    it->second.owner = this;
    c.record = &it->second;
    ++awaiting_hello_;
    auto verdict = admission_.admit_connection(clients_.size(), awaiting_hello_);
    if (auto* no = std::get_if<rejection>(&verdict)) {
        reject(c, *no);
        return false;
    }
    if (std::get<admission::connection_verdict>(verdict) == admission::connection_verdict::make_room) {
        if (connection* evicted = oldest_waiting_of_busiest_address(&c)) reject(*evicted, admission::waiting_evicted());
    }
    return true;
}

void match::release(connection& c) {
    auto it = clients_.find(&c);
    if (it == clients_.end() || it->second.standing.at != client_standing::stage::awaiting_hello) return;
    --awaiting_hello_;
    unlink(*it);
    clients_.erase(it);
}

bool match::waiting_for_hello(const connection& c) const {
    const auto it = clients_.find(&c);
    return it != clients_.end() && it->second.standing.at == client_standing::stage::awaiting_hello;
}

connection* match::oldest_waiting_of_busiest_address(const connection* newcomer) const {
    std::unordered_map<std::string_view, size_t> waiting;  // by address
    for (const auto& [c, cl] : clients_)
        if (cl.standing.at == client_standing::stage::awaiting_hello) ++waiting[cl.address];
    const client* chosen = nullptr;
    const connection* chosen_connection = nullptr;
    size_t chosen_count = 0;
    for (const auto& [c, cl] : clients_) {
        if (c == newcomer || cl.standing.at != client_standing::stage::awaiting_hello) continue;
        const size_t count = waiting[cl.address];
        // The busiest address first, then the oldest connection: a fixed choice (serials are unique).
        if (!chosen || count > chosen_count || (count == chosen_count && cl.serial < chosen->serial)) {
            chosen = &cl;
            chosen_connection = c;
            chosen_count = count;
        }
    }
    return const_cast<connection*>(chosen_connection);
}

bool match::on_hello(connection& c, client& cl, const protocol::hello_msg& hello) {
    auto who = admission_.admit_hello(hello, draining_);
    if (auto* no = std::get_if<rejection>(&who)) {
        reject(c, *no);
        return false;
    }
    admitted_hello& admitted = std::get<admitted_hello>(who);
    if (auto no = admission::admit_token_match(admitted, config_.match_id)) {
        reject(c, *no);
        return false;
    }
    if (admitted.spectator) return on_spectator_hello(c, cl, admitted);
    auto same = admitted.identity.empty() ? players_.end() : find_identity(admitted.identity);
    const std::optional<bool> same_connected =
        same == players_.end() ? std::nullopt : std::optional<bool>(same->second.who != nullptr);
    auto verdict = admission_.admit_join(same_connected, live_player_count());
    if (auto* no = std::get_if<rejection>(&verdict)) {
        reject(c, *no);
        return false;
    }
    world::player_id id;
    if (std::get<join_kind>(verdict) == join_kind::new_player) {
        if (players_.size() >= config_.admission.max_players) give_up_oldest_in_grace();
        id = world::player_id{next_player_id_++};
        players_.emplace(
            id, player{.who = &c,
                       .inputs = input_buffer(config_.input_buffer),
                       .snapshots = snapshot_client(baseline_ring(), hello.delta_snapshots, c.snapshot_budget()),
                       .body_id = {},
                       .game_sent = 0,
                       .events_from = game_.version(),
                       .disconnected_at_tick = 0,
                       .name = admitted.name,
                       .identity = admitted.identity});
        pending_joins_.push_back(id);
    } else {
        // The same player again: a reconnection, or a new connection taking over.
        id = same->first;
        player& p = same->second;
        connection* old = p.who;
        p.who = &c;  // first: the old connection's leave must not touch the player
        if (old) {
            if (auto old_it = clients_.find(old); old_it != clients_.end())
                forget(old_it, close_cause{close_cause::kind::taken_over, {}, {}});
            old->close_with_bye("signed in from another connection");
            ++counters_.takeovers;
        } else {
            ++counters_.reconnects;
        }
        p.inputs = input_buffer(config_.input_buffer);
        p.snapshots =
            snapshot_client(baseline_ring(), hello.delta_snapshots, c.snapshot_budget());  // holds no baseline yet
        p.game_sent = 0;
        p.events_from = game_.version();
        if (p.body_id) pending_welcomes_.push_back(id);
        log_("reconnect player=%u body=%u name=%s", id.value(), p.body_id.value(), p.name.c_str());
    }
    cl.player_id = id;
    cl.player = &players_.at(id);                     // a map's element stays where it is until erased
    cl.standing.at = client_standing::stage::joined;  // a new connection numbers its inputs from 1 again
    cl.standing.last_input_tick = world_.tick();      // the idle timeout starts now
    --awaiting_hello_;
    const std::string_view peer = c.peer();
    // The admitted name: the signed one with a token secret, never merely the claimed one.
    log_("hello player=%u name=%s from %.*s", id.value(), players_.at(id).name.c_str(), static_cast<int>(peer.size()),
         peer.data());
    return true;
}

bool match::on_spectator_hello(connection& c, client& cl, const admitted_hello& admitted) {
    if (auto no = admission_.admit_spectator(spectators_.size())) {
        reject(c, *no);
        return false;
    }
    // An id from the players' sequence, so that the Welcome's player_id is never 0 and names
    // nobody else; it never gets a body, so it is never on the scoreboard.
    const world::player_id id{next_player_id_++};
    // BodyState snapshots whatever the Hello asked: a delta is encoded against the view the
    // client acknowledged in its Inputs, and a spectator sends none. With the whole world as
    // the view (no view radius), that is the shared frame: one copy per spectator.
    spectator& s =
        spectators_
            .emplace(id, spectator{&c, admitted.name, snapshot_client(baseline_ring(), false, c.snapshot_budget()), 0,
                                   game_.version()})
            .first->second;
    cl.player_id = id;
    cl.standing.at = client_standing::stage::joined;
    cl.standing.spectator = true;
    cl.standing.last_input_tick = world_.tick();  // the idle timeout (kept off by Pings) starts now
    --awaiting_hello_;
    protocol::welcome_info welcome = welcome_for(id.value(), 0);  // entity_id 0: no body of its own
    welcome.view_radius = 0;                                      // its snapshots hold every body
    send_welcome(c, s.snapshots, welcome);
    const std::string_view peer = c.peer();
    log_("spectate id=%u name=%s from %.*s", id.value(), s.name.c_str(), static_cast<int>(peer.size()), peer.data());
    return true;
}

void match::give_up_oldest_in_grace() {
    auto oldest = players_.end();
    for (auto it = players_.begin(); it != players_.end(); ++it) {
        if (it->second.who) continue;
        if (oldest == players_.end() || it->second.disconnected_at_tick < oldest->second.disconnected_at_tick)
            oldest = it;  // ties: the lowest player id, the map's order
    }
    if (oldest != players_.end()) remove_player(oldest, "reconnect grace given up: a new player needed the slot");
}

std::vector<uint32_t> match::live_player_ids() const {
    std::vector<uint32_t> ids;
    for (const auto& [id, p] : players_)
        if (p.who) ids.push_back(id.value());
    return ids;
}

size_t match::players_in_grace() const {
    return static_cast<size_t>(
        std::count_if(players_.begin(), players_.end(), [](const auto& p) { return p.second.who == nullptr; }));
}

match::player_map::iterator match::find_identity(const std::string& identity) {
    for (auto it = players_.begin(); it != players_.end(); ++it)
        if (it->second.identity == identity) return it;
    return players_.end();
}

match::player_map::const_iterator match::find_identity(const std::string& identity) const {
    return const_cast<match*>(this)->find_identity(identity);
}

std::optional<rejection> match::seat_refusal(const protocol::hello_msg& hello, bool here) const {
    auto who = admission_.admit_hello(hello, draining_);
    if (auto* no = std::get_if<rejection>(&who)) return *no;
    const admitted_hello& admitted = std::get<admitted_hello>(who);
    if (here)
        if (auto no = admission::admit_token_match(admitted, config_.match_id)) return no;
    if (admitted.spectator) return admission_.admit_spectator(spectators_.size());
    const auto same = admitted.identity.empty() ? players_.end() : find_identity(admitted.identity);
    const std::optional<bool> same_connected =
        same == players_.end() ? std::nullopt : std::optional<bool>(same->second.who != nullptr);
    auto verdict = admission_.admit_join(same_connected, live_player_count());
    if (auto* no = std::get_if<rejection>(&verdict)) return *no;
    return std::nullopt;
}

protocol::welcome_info match::welcome_for(uint32_t player_id, uint32_t body_id) const {
    protocol::welcome_info welcome;
    welcome.player_id = player_id;
    welcome.entity_id = body_id;
    welcome.tick = world_.tick();
    welcome.tick_rate = config_.tick_rate;
    welcome.snapshot_rate = config_.snapshot_rate;
    welcome.preset = config_.preset;
    welcome.world_config = world_config_json_;
    welcome.world_config_hash = world_config_hash_;
    welcome.world_version = world::world_version;
    welcome.view_radius = config_.view_radius;
    welcome.statics = static_geometry(world_, kinds_);
    welcome.match = config_.match_id;
    welcome.mode = config_.mode;
    welcome.game = manifest_;
    return welcome;
}

void match::send_welcome(world::player_id id, player& p) {
    send_welcome(*p.who, p.snapshots, welcome_for(id.value(), p.body_id.value()));
}

void match::send_welcome(connection& c, snapshot_client& snapshots, const protocol::welcome_info& welcome) {
    const auto bodies = world_.bodies();
    // Ids grow: a static body added later has an id past this, and snapshots describe it.
    snapshots.shapes.welcomed(bodies.empty() ? 0 : bodies.back().id + 1);
    if (outbox_) {
        outbox_->send(c, protocol::encode_welcome(welcome));
    } else {
        c.send(protocol::encode_welcome(welcome));
    }
}

}  // namespace arena::match
