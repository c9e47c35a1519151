#include "server/match/match.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "games/registry.hpp"
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

}  // namespace

match::match(const match_config& config, const world::world_config& world_config, logger log, token_check check_token)
    : config_(config),
      log_(std::move(log)),
      admission_(config.admission, config.tick_rate, std::move(check_token)),
      world_(world_config, config.seed),
      rules_(games::make_rules(world_)),
      manifest_(rules_->manifest()),
      world_config_json_(config::config_to_json(world_config)),
      world_config_hash_(protocol::world_config_hash(world_config_json_)),
      fanout_({config.view_radius, baseline_ring(), config.tick_rate}),
      // Events are kept for a few seconds of lost snapshots (each client's acknowledgements
      // say what it holds, however old), at least as long as a delta baseline.
      game_(std::max(config.delta_history * snapshot_interval(), event_memory_s * config.tick_rate)) {
    // A game's manifest is its code's: one that breaks the protocol's bounds is a bug in the game.
    if (const std::string bad = protocol::manifest_problem(manifest_); !bad.empty())
        throw std::invalid_argument("the game's manifest: " + bad);
    game_.declare(manifest_.player_fields.size(), manifest_.team_fields.size());
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
    for (unsigned kind = 0; kind < 256; ++kind)
        kinds_.set_weight(static_cast<uint8_t>(kind), rules_->snapshot_weight(static_cast<uint8_t>(kind)));
}

match::~match() {
    // A connection may outlive the match it was in (its transport closes it later): it must
    // not keep a record that is gone. One that ended first said so (~connection).
    for (const auto& entry : clients_) unlink(entry);
}

uint32_t match::snapshot_interval() const {
    return std::max<uint32_t>(1, config_.tick_rate / std::max<uint16_t>(1, config_.snapshot_rate));
}

uint32_t match::player_of(const connection& c) const {
    auto it = clients_.find(&c);
    return it == clients_.end() ? 0 : it->second.player_id.value();
}

bool match::receive(connection& c, const protocol::Message& message) {
    const int64_t tick_ns = 1'000'000'000LL / std::max<uint16_t>(1, config_.tick_rate);
    return receive(c, message, static_cast<int64_t>(world_.tick()) * tick_ns);
}

bool match::receive(connection& c, const protocol::Message& message, int64_t arrival_ns, int64_t held_ns) {
    // Bytes that were on their way when it was closed, or a connection this match never held.
    if (!c.record || c.record->owner != this) return false;
    client& cl = *c.record;
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
    forget(clients_.find(&c), close_cause{close_cause::kind::client_bye, {}, std::get<bye_message>(admitted).reason});
    return false;
}

bool match::on_input(connection& c, client& cl, const protocol::input_msg& input, int64_t arrival_ns) {
    if (!cl.player) return true;
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
    player& p = *cl.player;
    p.snapshots.acknowledge(input.snapshot_ack);
    for (const sequenced_input& earlier : in.recovered) p.inputs.push(earlier);
    counters_.inputs_recovered += in.recovered.size();
    counters_.inputs_lost += in.lost;
    p.inputs.push({input.sequence, in.input, in.view});
    return true;
}

void match::reject(connection& c, const rejection& why) {
    auto it = clients_.find(&c);
    if (it == clients_.end()) return;  // already closed: one last word only
    const char* code = protocol::EnumNameRejectCode(why.code);
    const std::string_view peer = c.peer();
    log_("reject %.*s code=%s reason=%s", static_cast<int>(peer.size()), peer.data(), code, why.detail.c_str());
    ++counters_.rejects[why.code];
    forget(it, close_cause::of(why));
    if (outbox_) {
        outbox_->close(c, why.code, why.detail);
    } else {
        c.close(why.code, why.detail);
    }
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
    protocol::match_result r = game_.result(rules_->winner());
    r.winning_team = rules_->winning_team();
    r.winners = rules_->winners();
    return r;
}

void match::forget(client_map::iterator it, const close_cause& cause) {
    ++counters_.closes[cause.key()];
    const connection* c = it->first;
    const world::player_id player_id = it->second.player_id;
    if (it->second.standing.at == client_standing::stage::awaiting_hello) --awaiting_hello_;
    unlink(*it);
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
    if (p.who && p.who->record) p.who->record->player = nullptr;  // its client, if any, plays no more
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
        if (!p.body_id) continue;
        world::player_input input = p.who ? p.inputs.consume() : world::player_input{};
        if (p.who) input.rewind = rewind_of(p.inputs.last_consumed_view());
        record.inputs.push_back({p.body_id, input});
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
        game_.update(world_.tick(), board, rules_->events(), names_, rules_->teams(), rules_->declared_events());
        if (config_.score_limit > 0)
            for (const rules::score_line& line : board) over_ = over_ || line.score >= config_.score_limit;
        over_ = over_ || rules_->finished();
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
    total.max_players = config_.admission.max_players;
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

uint16_t match::rewind_of(uint64_t view) const {
    const uint64_t cap =
        std::min<uint64_t>(uint64_t{config_.lag_compensation_ms} * config_.tick_rate * 256 / 1000, world::max_rewind);
    const uint64_t now = uint64_t{world_.tick()} * 256;
    if (view == 0 || view >= now) return 0;
    return static_cast<uint16_t>(std::min(now - view, cap));
}

}  // namespace arena::match
