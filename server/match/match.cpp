#include "server/match/match.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "protocol/config_hash.hpp"
#include "protocol/version.hpp"
#include "server/config/config_json.hpp"
#include "server/match/logger.hpp"
#include "server/match/shape_wire.hpp"

namespace arena::match {

using protocol::RejectCode;

namespace {

// Seconds of game events a client that hears nothing can still catch up on: a loss of
// snapshots that long, while its inputs still arrive (longer, the connection is as good as
// gone). Events are small: 28 bytes each, a few a second.
constexpr uint32_t event_memory_s = 10;

admission_limits limits_of(const match_config& c) {
    admission_limits l;
    l.tick_rate = c.tick_rate;
    l.max_players = c.max_players;
    l.max_spectators = c.max_spectators;
    l.max_connections = c.max_connections;
    l.max_pending_handshakes = c.max_pending_handshakes;
    l.handshake_timeout_ticks =
        std::max<uint32_t>(1, static_cast<uint32_t>(std::ceil(c.handshake_timeout_s * c.tick_rate)));
    l.idle_timeout_ticks =
        c.idle_timeout_s <= 0 ? 0
                              : std::max<uint32_t>(1, static_cast<uint32_t>(std::ceil(c.idle_timeout_s * c.tick_rate)));
    l.max_name_bytes = c.max_name_bytes;
    l.max_token_bytes = c.max_token_bytes;
    l.max_inputs_per_second = c.max_inputs_per_second;
    return l;
}

}  // namespace

match::match(const match_config& config, const world::world_config& world_config, logger log, token_check check_token)
    : config_(config),
      log_(std::move(log)),
      admission_(limits_of(config), std::move(check_token)),
      world_(world_config, config.seed),
      rules_(rules::make_rules(world_)),
      world_config_json_(config::config_to_json(world_config)),
      world_config_hash_(protocol::world_config_hash(world_config_json_)),
      fanout_({config.view_radius, baseline_ring(), config.tick_rate}),
      // Events are kept for a few seconds of lost snapshots (each client's acknowledgements
      // say what it holds, however old), at least as long as a delta baseline.
      game_(std::max(config.delta_history * snapshot_interval(), event_memory_s * config.tick_rate)) {
    // The Welcome tells clients the snapshot rate; it must be the rate they get.
    if (config.tick_rate == 0 || config.snapshot_rate == 0 || config.tick_rate % config.snapshot_rate != 0)
        throw std::invalid_argument("snapshot rate " + std::to_string(config.snapshot_rate) +
                                    " does not divide the tick rate " + std::to_string(config.tick_rate));
    // Every Welcome carries the static geometry: a world whose Welcome a client would refuse
    // as too large does not start (config limits keep configs far below it; a world built
    // otherwise might not be).
    const size_t welcome_bytes = protocol::encode_welcome(welcome_for(1, 1)).size() - protocol::frame_prefix_size;
    if (welcome_bytes > protocol::max_server_frame_body)
        throw std::invalid_argument("the world's configuration and static geometry make a Welcome of " +
                                    std::to_string(welcome_bytes) + " bytes, above the " +
                                    std::to_string(protocol::max_server_frame_body) + " a client accepts");
}

uint32_t match::snapshot_interval() const {
    return std::max<uint32_t>(1, config_.tick_rate / std::max<uint16_t>(1, config_.snapshot_rate));
}

uint32_t match::player_of(const connection& c) const {
    auto it = clients_.find(&c);
    return it == clients_.end() ? 0 : it->second.player_id.value();
}

bool match::connect(connection& c) {
    client cl;
    cl.serial = next_serial_++;
    cl.address = std::string(c.address());
    cl.standing.connected_tick = world_.tick();
    auto [it, inserted] = clients_.emplace(&c, cl);
    if (!inserted) return true;  // already known: a transport bug, but harmless
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

bool match::receive(connection& c, const protocol::Message& message) {
    const int64_t tick_ns = 1'000'000'000LL / std::max<uint16_t>(1, config_.tick_rate);
    return receive(c, message, static_cast<int64_t>(world_.tick()) * tick_ns);
}

bool match::receive(connection& c, const protocol::Message& message, int64_t arrival_ns, int64_t held_ns) {
    auto it = clients_.find(&c);
    if (it == clients_.end()) return false;  // bytes that were on their way when it was closed
    client& cl = it->second;
    admitted_message admitted = admission_.admit_message(cl.standing, message);
    if (auto* no = std::get_if<rejection>(&admitted)) {
        reject(c, *no);
        return false;
    }
    if (auto* m = std::get_if<hello_message>(&admitted)) return on_hello(c, cl, m->hello);
    if (auto* m = std::get_if<input_message>(&admitted)) return on_input(c, cl, m->input, arrival_ns);
    if (auto* m = std::get_if<ping_message>(&admitted)) {
        if (auto no = admission_.admit_ping(cl.standing, arrival_ns, world_.tick())) {
            reject(c, *no);
            return false;
        }
        // µs, at most an hour's worth (a clock step must not wrap the field).
        const std::optional<uint32_t> held_us =
            held_ns < 0
                ? std::nullopt
                : std::optional<uint32_t>(static_cast<uint32_t>(std::min<int64_t>(held_ns / 1000, 3'600'000'000)));
        c.send(protocol::encode_pong(m->client_time, world_.tick(), held_us));
        return true;
    }
    forget(it, close_cause{close_cause::kind::client_bye, {}, std::get<bye_message>(admitted).reason});
    return false;
}

bool match::on_hello(connection& c, client& cl, const protocol::hello_msg& hello) {
    auto who = admission_.admit_hello(hello, draining_);
    if (auto* no = std::get_if<rejection>(&who)) {
        reject(c, *no);
        return false;
    }
    admitted_hello& admitted = std::get<admitted_hello>(who);
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
        if (players_.size() >= config_.max_players) give_up_oldest_in_grace();
        id = world::player_id{next_player_id_++};
        players_.emplace(id, player{&c,
                                    admitted.name,
                                    admitted.identity,
                                    0,
                                    {},
                                    input_buffer(config_.input_buffer),
                                    snapshot_client(baseline_ring(), hello.delta_snapshots, c.snapshot_budget()),
                                    0,
                                    game_.version()});
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

size_t match::players_in_grace() const {
    return static_cast<size_t>(
        std::count_if(players_.begin(), players_.end(), [](const auto& p) { return p.second.who == nullptr; }));
}

bool match::on_input(connection& c, client& cl, const protocol::input_msg& input, int64_t arrival_ns) {
    auto it = players_.find(cl.player_id);
    if (it == players_.end()) return true;
    ++counters_.inputs_received;
    auto admitted = admission_.admit_input(cl.standing, input, arrival_ns, world_.tick());
    if (auto* no = std::get_if<rejection>(&admitted)) {
        reject(c, *no);
        return false;
    }
    const admitted_input& in = std::get<admitted_input>(admitted);
    if (in.stale) {
        ++counters_.stale_inputs;
        return true;
    }
    player& p = it->second;
    p.snapshots.acknowledge(input.snapshot_ack);
    for (const sequenced_input& earlier : in.recovered) p.inputs.push(earlier);
    counters_.inputs_recovered += in.recovered.size();
    counters_.inputs_lost += in.lost;
    p.inputs.push({input.sequence, in.input});
    return true;
}

match::player_map::iterator match::find_identity(const std::string& identity) {
    for (auto it = players_.begin(); it != players_.end(); ++it)
        if (it->second.identity == identity) return it;
    return players_.end();
}

void match::reject(connection& c, const rejection& why) {
    auto it = clients_.find(&c);
    if (it == clients_.end()) return;  // already closed: one last word only
    const char* code = protocol::EnumNameRejectCode(why.code);
    const std::string_view peer = c.peer();
    log_("reject %.*s code=%s reason=%s", static_cast<int>(peer.size()), peer.data(), code, why.detail.c_str());
    ++counters_.rejects[why.code];
    forget(it, close_cause::of(why));
    c.close(why.code, why.detail);
}

void match::disconnect(connection& c, const close_cause& cause) {
    if (auto it = clients_.find(&c); it != clients_.end()) forget(it, cause);
}

void match::shut_down(std::string_view reason) {
    draining_ = true;
    std::vector<std::pair<uint64_t, connection*>> all;
    for (auto& [c, cl] : clients_) all.emplace_back(cl.serial, const_cast<connection*>(c));
    std::sort(all.begin(), all.end());
    const protocol::match_result end = result();
    for (auto& [serial, c] : all) {
        forget(clients_.find(c), close_cause{close_cause::kind::shutdown, {}, std::string(reason)});
        if (end.over) {
            c->close_with_result(reason, end);
        } else {
            c->close_with_bye(reason);
        }
    }
}

protocol::match_result match::result() const {
    if (!rules_->has_state()) return {};
    return game_.result(rules_->winner());
}

void match::forget(client_map::iterator it, const close_cause& cause) {
    ++counters_.closes[cause.key()];
    const connection* c = it->first;
    const world::player_id player_id = it->second.player_id;
    if (it->second.standing.at == client_standing::stage::awaiting_hello) --awaiting_hello_;
    clients_.erase(it);
    if (!player_id) return;
    if (auto s = spectators_.find(player_id); s != spectators_.end()) {
        log_("spectator leaves id=%u name=%s reason=%s", player_id.value(), s->second.name.c_str(),
             cause.text().c_str());
        spectators_.erase(s);
        return;
    }
    auto p = players_.find(player_id);
    if (p != players_.end() && p->second.who == c) leave(p, cause);
}

void match::leave(player_map::iterator it, const close_cause& cause) {
    player& p = it->second;
    const std::string reason = cause.text();
    if (cause.connection_lost() && !draining_ && !p.identity.empty() && p.body_id && config_.reconnect_grace_s > 0) {
        p.who = nullptr;
        p.disconnected_at_tick = world_.tick();
        log_("disconnect player=%u name=%s reason=%s (body kept for %.0f s)", it->first.value(), p.name.c_str(),
             reason.c_str(), config_.reconnect_grace_s);
        return;
    }
    remove_player(it, reason);
}

void match::remove_player(player_map::iterator it, std::string_view reason) {
    player& p = it->second;
    if (p.body_id) {
        pending_leaves_.push_back(p.body_id);
    } else {
        std::erase(pending_joins_, it->first);
    }
    std::erase(pending_welcomes_, it->first);
    counters_.input_underruns += p.inputs.underruns();
    counters_.input_overflows += p.inputs.overflows();
    ++counters_.leaves;
    log_("leave player=%u name=%s reason=%.*s", it->first.value(), p.name.c_str(), static_cast<int>(reason.size()),
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

void match::tick() {
    expire_disconnected();
    tick_record record;
    record.tick = world_.tick();
    record.joins = pending_joins_;
    for (const world::player_id id : record.joins) {
        const auto joining = players_.find(id);
        record.join_names.push_back(joining == players_.end() ? std::string() : joining->second.name);
    }
    record.leaves = pending_leaves_;
    pending_joins_.clear();
    pending_leaves_.clear();
    for (auto& [id, p] : players_) {
        // A disconnected player's body coasts: no thrust, no turn, no buttons.
        if (p.body_id) record.inputs.push_back({p.body_id, p.who ? p.inputs.consume() : world::player_input{}});
    }
    const std::vector<world::body_id> spawned = apply_tick(world_, *rules_, record);
    if (on_tick) on_tick(record, rules::state_hash(world_, *rules_));
    spawn_pending(record.joins, spawned);
    // A ship the rules respawned is the player's body from now on; a player without one keeps
    // its last body id (snapshots then show an empty view, and a leave names that body).
    for (auto& [id, p] : players_)
        if (const uint32_t body = rules_->body_of(id.value()); body != 0) p.body_id = world::body_id{body};
    tag_new_bodies();
    if (rules_->has_state()) {
        const std::vector<rules::score_line> board = rules_->scoreboard();
        game_.update(world_.tick(), board, rules_->events(), names_);
        if (config_.score_limit > 0)
            for (const rules::score_line& line : board) over_ = over_ || line.score >= config_.score_limit;
    }
    // Taken out of the list first: a send may end a connection (a Reject while sending), whose
    // leave erases from pending_welcomes_, or take a player over, which adds to it; walking the
    // list itself then skipped a reconnected player's Welcome.
    const std::vector<world::player_id> welcomes = std::exchange(pending_welcomes_, {});
    for (const world::player_id id : welcomes) {
        auto it = players_.find(id);
        if (it != players_.end() && it->second.who) send_welcome(id, it->second);
    }

    check_clients();
    send_snapshots();
}

void match::tag_new_bodies() {
    if (!rules_->has_state()) return;  // sandbox rules tag nothing
    // Ids only grow, and bodies are in id order: the new ones are the tail.
    const std::span<const world::body> bodies = world_.bodies();
    auto it = std::lower_bound(bodies.begin(), bodies.end(), kinds_asked_below_,
                               [](const world::body& b, uint32_t id) { return b.id < id; });
    for (; it != bodies.end(); ++it) {
        if (const uint8_t kind = rules_->kind_of(it->id); kind != 0) kinds_.set(it->id, kind);
        if (const rules::shot_record* shot = rules_->shot_of(it->id)) record_origin(it->id, *shot);
    }
    if (!bodies.empty()) kinds_asked_below_ = std::max(kinds_asked_below_, bodies.back().id + 1);
}

void match::record_origin(uint32_t body_id, const rules::shot_record& shot) {
    const auto p = players_.find(world::player_id{shot.shooter});
    if (p == players_.end()) return;
    const float values[] = {shot.position.x(), shot.position.y(), shot.velocity.x(), shot.velocity.y()};
    // A diverged world's NaN stays off the wire, as snapshot encoders keep it out of BodyState.
    for (const float v : values)
        if (!std::isfinite(v)) return;
    // The tick that fired it consumed this input: the bullet appeared in it.
    origins_.add(
        {body_id, shot.shooter, p->second.inputs.last_consumed_sequence(), values[0], values[1], values[2], values[3]});
}

void match::check_clients() {
    struct refusal {
        uint64_t serial;
        connection* who;
        rejection why;
    };
    std::vector<refusal> refused;
    for (auto& [c, cl] : clients_)
        if (auto no = admission_.check_on_tick(cl.standing, world_.tick()))
            refused.push_back({cl.serial, const_cast<connection*>(c), std::move(*no)});
    std::sort(refused.begin(), refused.end(), [](const refusal& a, const refusal& b) { return a.serial < b.serial; });
    for (const refusal& r : refused) reject(*r.who, r.why);
}

void match::spawn_pending(const std::vector<world::player_id>& owners, const std::vector<world::body_id>& bodies) {
    for (size_t i = 0; i < owners.size(); ++i) {
        auto it = players_.find(owners[i]);
        if (it == players_.end()) continue;
        player& p = it->second;
        if (!bodies[i]) {
            if (p.who) reject(*p.who, {RejectCode::server_full, "the world has no room for another body"});
            continue;
        }
        p.body_id = bodies[i];
        names_[owners[i]] = p.name;
        ++counters_.joins;
        counters_.players_peak = std::max<uint32_t>(counters_.players_peak, static_cast<uint32_t>(players_.size()));
        if (p.who) send_welcome(owners[i], p);
        log_("join player=%u body=%u name=%s", owners[i].value(), p.body_id.value(), p.name.c_str());
    }
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
    return welcome;
}

void match::send_welcome(world::player_id id, player& p) {
    send_welcome(*p.who, p.snapshots, welcome_for(id.value(), p.body_id.value()));
}

void match::send_welcome(connection& c, snapshot_client& snapshots, const protocol::welcome_info& welcome) {
    const auto bodies = world_.bodies();
    // Ids grow: a static body added later has an id past this, and snapshots describe it.
    snapshots.shapes.welcomed(bodies.empty() ? 0 : bodies.back().id + 1);
    c.send(protocol::encode_welcome(welcome));
}

void match::send_snapshots() {
    // BodyState clients all get theirs on the ticks that are multiples of the interval (one
    // shared frame when they see the whole world). Delta clients cost a view query and an
    // encoding each, so they are spread over the interval by player id: a third of them on
    // each tick at 60 Hz ticks and 20 Hz snapshots, not all of them on one tick.
    const uint32_t interval = snapshot_interval();
    const uint32_t phase = world_.tick() % interval;
    kinds_.forget_missing(world_.bodies());
    origins_.forget_missing(world_.bodies());
    // The shared frame (BodyState clients of whole-world views, on the interval's ticks)
    // carries what changed since the previous one: its clients got that one.
    const bool shared_due = phase == 0 && fanout_.shared_full_frame() && !game_.empty();
    if (shared_due) shared_game_through_ = game_.collect(shared_game_sent_, shared_game_sent_, shared_game_);
    fanout_.begin(world_, &kinds_, shared_due ? &shared_game_ : nullptr, &origins_);
    // By id rather than by iterator: a send may end a connection, and with it a player.
    for (auto it = players_.begin(); it != players_.end();) {
        const world::player_id id = it->first;
        player& p = it->second;
        if (p.body_id && p.who && (p.snapshots.delta ? id.value() % interval : 0) == phase) {
            const size_t waiting = p.inputs.waiting();
            p.snapshots.extra_inputs_waiting =
                static_cast<uint16_t>(waiting > 1 ? std::min<size_t>(waiting - 1, 65535) : 0);
            send_snapshot(p, p.body_id, p.inputs.last_consumed_sequence());
        }
        it = players_.upper_bound(id);
    }
    // Spectators, BodyState clients all, on the interval's ticks, after the players.
    if (phase == 0) {
        for (auto it = spectators_.begin(); it != spectators_.end();) {
            const world::player_id id = it->first;
            send_snapshot(it->second, world::body_id{}, 0);  // no body: the whole world; no input to acknowledge
            it = spectators_.upper_bound(id);
        }
    }
    // The fan-out builds the shared frame only for a client that takes it.
    if (shared_due && fanout_.last_shared_tick() == world_.tick()) shared_game_sent_ = shared_game_through_;
}

template <class Reader>
const protocol::game_list* match::game_for(const Reader& r, uint32_t& through) {
    if (game_.empty()) return nullptr;
    uint32_t held = 0;
    if (r.snapshots.delta) {
        held = r.snapshots.game_held;  // what its acknowledged snapshots brought
    } else {
        held = r.game_sent;  // a stream: what was sent arrived
    }
    // Within a datagram the game takes at most half: the bodies keep the rest.
    const size_t game_budget = r.snapshots.budget / 2;
    through = game_.collect(held, r.events_from, game_list_, game_budget);
    return &game_list_;
}

template <class Reader>
void match::send_snapshot(Reader& r, world::body_id own, uint32_t ack) {
    ++counters_.snapshots_sent;
    if (!r.snapshots.delta && fanout_.shared_full_frame()) {
        if (const protocol::snapshot_encoder* shared = fanout_.shared_frame(r.snapshots)) {
            counters_.snapshot_bytes = shared->frame().size();
            r.game_sent = shared_game_through_;
            r.who->send_snapshot(*shared, ack);  // one memcpy, the ack patched in
            return;
        }
    }
    uint32_t through = 0;
    const protocol::game_list* game = game_for(r, through);
    if (!r.snapshots.delta) r.game_sent = through;
    const auto frame = r.snapshots.delta ? fanout_.delta_frame(r.snapshots, own, ack, game)
                                         : fanout_.full_frame(r.snapshots, own, ack, game);
    if (r.snapshots.delta) r.snapshots.views.record_game(world_.tick(), through);
    counters_.snapshot_bytes = frame.size();
    r.who->send_snapshot_frame(frame);
}

std::vector<match::named_score> match::scoreboard() const {
    std::vector<named_score> out;
    for (const rules::score_line& line : rules_->scoreboard()) {
        const auto it = names_.find(world::player_id{line.player});
        out.push_back({it == names_.end() ? std::string() : it->second, line});
    }
    return out;
}

match_counters match::counters() const {
    match_counters total = counters_;
    total.ticks = world_.tick();
    total.players = live_player_count();  // live connections only: bodies in the grace are counted apart
    total.players_in_grace = players_in_grace();
    total.max_players = config_.max_players;
    total.spectators = spectators_.size();
    for (const rules::score_line& line : rules_->scoreboard()) {
        total.shots += line.shots;
        total.hits += line.hits;
        total.kills += line.kills;
    }
    total.snapshots = fanout_.counters();
    for (const auto& [id, p] : players_) {
        total.input_underruns += p.inputs.underruns();
        total.input_overflows += p.inputs.overflows();
    }
    return total;
}

}  // namespace arena::match
