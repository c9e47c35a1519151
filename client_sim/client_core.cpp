#include "client_sim/client_core.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "client_sim/wire.hpp"
#include "games/asteroids/asteroids_params.hpp"
#include "games/asteroids/asteroids_rules.hpp"
#include "games/registry.hpp"
#include "server/rules/hit_history.hpp"

namespace arena::bots {

namespace {

// A server that stops reading our inputs would make pending_ grow without end.
constexpr std::size_t max_pending_bytes = 1 << 20;

// `values` into `held` by owner (a player id, or a team number), only fields the manifest has: a
// value past them, or an owner past Owner's range, is the server's bug and is left out rather
// than trusted.
template <class Owner>
void keep_values(std::map<Owner, client_core::declared_values>& held, std::span<const protocol::game_value> values,
                 std::size_t fields) {
    for (const protocol::game_value& v : values)
        if (v.field < fields && v.owner <= std::numeric_limits<Owner>::max())
            held[static_cast<Owner>(v.owner)][v.field] = v.value;
}

// The first `fields` of `held`: a declared line as a scoreboard keeps it.
std::vector<std::int32_t> first_fields(const client_core::declared_values& held, std::size_t fields) {
    return std::vector<std::int32_t>(held.begin(), held.begin() + static_cast<std::ptrdiff_t>(fields));
}

// The circle around a body's shape (m), as the server's hit history keeps a target: every shape
// is a core of vertices swept by a disc of `radius` (a circle's one vertex is its centre).
float bounding_radius(const protocol::shape_desc& shape) {
    float core2 = 0;
    for (std::size_t i = 0; i < shape.vertex_count && i < protocol::max_shape_vertices; ++i)
        core2 = std::max(core2, shape.xy[2 * i] * shape.xy[2 * i] + shape.xy[2 * i + 1] * shape.xy[2 * i + 1]);
    return std::sqrt(core2) + shape.radius;
}

}  // namespace

client_core::client_core(client_shared& shared, client_params params)
    : shared_(shared),
      params_(std::move(params)),
      session_({.delta_snapshots = params_.delta_snapshots,
                .unordered = params_.unordered,
                .lenient = params_.mode != misbehavior::none},
               &shared),
      frames_(protocol::max_server_frame_body),
      fault_rng_(params_.seed ^ (0xa0761d6478bd642fULL * (std::uint64_t{params_.index} + 1))) {
    outcome_.misbehaving = params_.mode != misbehavior::none;
    outcome_.name = params_.name;
}

void client_core::launch(time_ns now) {
    launched_at_ = now;
    if (phase_ == phase::idle) phase_ = phase::connecting;
}

void client_core::connected() {
    if (phase_ != phase::connecting) return;
    phase_ = phase::joining;
    queue(session_.hello(params_.name, params_.token, params_.join_match, params_.join_mode));
}

void client_core::on_bytes(std::span<const std::uint8_t> data, time_ns now) {
    while (!data.empty() && phase_ != phase::ended) {
        data = data.subspan(frames_.feed(data));
        if (frames_.failed())
            return end(end_kind::protocol_error, "bad frame from the server: " + std::string(frames_.error()));
        if (frames_.has_frame()) {
            after_frame(session_.handle(frames_.frame()), frames_.frame().size(), now);
            frames_.next();
        }
    }
}

void client_core::on_frame(std::span<const std::uint8_t> frame, time_ns now) {
    if (phase_ == phase::ended) return;
    after_frame(session_.feed(frame), frame.size(), now);
}

void client_core::flushed() {
    if (close_after_flush_ && pending_.empty()) end(end_kind::orderly, close_reason_);
}

void client_core::queue(std::span<const std::uint8_t> bytes) {
    pending_.insert(pending_.end(), bytes.begin(), bytes.end());
}

void client_core::after_frame(protocol::Payload handled, std::size_t frame_bytes, time_ns now) {
    using protocol::Payload;
    if (session_.stale()) {
        ++shared_.metrics().stale_messages;  // a duplicate, overtaken, or ahead of the Welcome
        return;
    }
    if (handled == Payload::Welcome) on_welcome();
    if (handled == Payload::Snapshot) on_snapshot(frame_bytes, now);
    if (handled == Payload::Pong) on_pong(now);
    if (handled == Payload::Reject) {
        // The figures count "code: reason", the session's error without its "Reject ".
        ++shared_.metrics().rejects[session_.error().substr(std::string_view("Reject ").size())];
        outcome_.server_goodbye = session_.reject_code() == protocol::RejectCode::shutting_down;
    }
    // An orderly goodbye (the server's match is over, or it is stopping), not a fault.
    if (handled == Payload::Bye) outcome_.server_goodbye = true;
    if (session_.ended())
        end(session_.how_ended() == session::end_kind::by_server ? end_kind::by_server : end_kind::protocol_error,
            session_.error());
}

void client_core::on_welcome() {
    behavior_.emplace(params_.kind, params_.seed, params_.index, *session_.config());
    if (params_.kind == behavior_kind::game)
        if (const rules::game_definition* game = games::find(session_.config()->rules); game && game->make_bot)
            game_bot_ = game->make_bot(params_.seed, params_.index);
    phase_ = phase::playing;
    // Hit registration: Asteroids' targets (ships and rocks), for a player that plays fair.
    judge_hits_ = session_.config()->rules == "asteroids" && !outcome_.misbehaving;
    hits_.set_window(session_.tick_rate());  // a second of ticks
    shown_.set_interval(
        std::max<std::uint32_t>(1, session_.tick_rate() / std::max<std::uint16_t>(1, session_.snapshot_rate())));
    outcome_.joined = true;
    shared_.on_joined(session_.welcome());
}

void client_core::on_snapshot(std::size_t frame_bytes, time_ns now) {
    fleet_metrics& m = shared_.metrics();
    ++m.snapshots;
    ++m.interval_snapshots;
    if (snapshots_++ == 0) {
        first_snapshot_at_ = now;
    } else if (!outcome_.misbehaving) {
        m.snapshot_gap_ms.add(static_cast<double>(now - last_snapshot_at_) / 1e6);
    }
    last_snapshot_at_ = now;
    m.snapshot_bytes_each.add(static_cast<double>(frame_bytes));
    m.snapshot_bytes += frame_bytes;

    // A delta that does not decode still brings its shapes and the game.
    m.shapes_received += session_.arrived().size();
    m.shape_bytes += session_.arrived().size() * sizeof(protocol::BodyShape);
    for (const protocol::shape_desc& d : session_.arrived())
        m.shape_bytes += d.vertex_count * sizeof(protocol::ShapeVertex);
    take_game();
    if (session_.was_delta()) {
        ++m.delta_snapshots;
        if (!session_.delta_problem().empty()) {
            // The receiver dropped its baselines, so the next ack (0) brings a full view.
            ++m.delta_errors;
            ++m.delta_problems[session_.delta_problem()];
            return;
        }
        m.delta_payload_bytes += session_.delta_bytes();
        m.delta_bodies += session_.view().size();
    }
    if (first_view_tick_ == 0) first_view_tick_ = session_.view_tick();
    hits_.advance(session_.view_tick());
    if (judge_hits_) shown_.on_snapshot(session_.view_tick(), session_.predicted_tick(), session_.view());
    const std::vector<protocol::BodyState>& bodies = session_.view();
    m.bodies_in_view.add(static_cast<double>(bodies.size()));
    m.view_bodies += bodies.size();
    check_shapes(bodies);

    if (!outcome_.misbehaving) {
        const predictor::correction& c = session_.correction();
        if (c.error) {
            m.prediction_error_m.add(*c.error);
            if (*c.error == 0.0f) ++m.predictions_exact;
            m.interval_prediction_error_m.add(*c.error);
        }
        m.input_lag_ticks.add(static_cast<double>(session_.last_sequence() - session_.view_ack()));
        for (const float e : session_.shot_errors()) m.own_shot_error_m.add(e);
    }
    behavior_->observe(bodies, session_.entity_id());
}

void client_core::lost_to_shot(const protocol::game_event& lost) {
    // A rewound hit told its rewind just before (shot_rewound); any other was judged at once.
    std::uint32_t rewind = 0;
    if (const auto it = rewound_hits_.find(lost.body); it != rewound_hits_.end()) {
        rewind = it->second;
        rewound_hits_.erase(it);
    }
    if (!judge_hits_ || session_.tick_rate() == 0) return;
    // The client shows its own ship at its predicted tick; it was hit as it was at the event's
    // tick less the rewind: the difference is how long it saw itself alive, perhaps clear.
    const std::int64_t hit_at = std::int64_t{lost.tick} * 256 - rewind;
    const std::int64_t shown = std::int64_t{session_.predicted_tick()} * 256;
    shared_.metrics().hit_after_seen_ms.add(static_cast<double>(shown - hit_at) * 1000.0 /
                                            (256.0 * session_.tick_rate()));
}

void client_core::take_game() {
    const protocol::game_list& game = session_.game();
    if (game.empty()) return;
    fleet_metrics& m = shared_.metrics();
    m.game_bytes += game.wire_bytes();
    for (std::size_t i = 0; i < game.name_ids.size(); ++i) names_[game.name_ids[i]] = game.names[i];
    for (const protocol::player_row& row : game.players) players_[row.player] = row;
    std::uint32_t last = session_.events_taken_before();
    for (const protocol::game_event& e : game.events) {
        if (e.sequence <= last) continue;  // taken from an earlier snapshot
        last = e.sequence;
        ++m.game_events;
        const std::uint32_t me = session_.player_id();
        if (e.kind == protocol::GameEventKind::rock_hit && e.player == me) hits_.server_hit(e.body, e.tick);
        if (e.kind == protocol::GameEventKind::ship_destroyed && e.other == me) hits_.server_hit(e.body, e.tick);
        if ((e.kind == protocol::GameEventKind::rock_hit && e.player != me) ||
            (e.kind == protocol::GameEventKind::ship_destroyed && e.other != me))
            hits_.other_hit(e.body, e.tick);
        if (judge_hits_ &&
            (e.kind == protocol::GameEventKind::rock_hit || e.kind == protocol::GameEventKind::ship_destroyed))
            shown_.went(e.body, e.tick);
        if (judge_hits_ && e.kind == protocol::GameEventKind::respawn) shown_.came(e.body, e.tick);
        if (e.kind == protocol::GameEventKind::shot_rewound && e.player == me) rewound_hits_[e.body] = e.value;
        if (e.kind == protocol::GameEventKind::ship_destroyed && e.player == me && e.other != 0) lost_to_shot(e);
        if (e.kind == protocol::GameEventKind::respawn) {
            // Kept while the ship may still be invulnerable: a bounded map.
            std::erase_if(respawned_, [&](const auto& r) { return r.second + invulnerable_ticks() <= e.tick; });
            respawned_[e.body] = e.tick;
        }
        events_.push_back(e);
        if (events_.size() > max_kept_events) events_.pop_front();
    }
    keep_values(player_values_, game.player_values, manifest().player_fields.size());
    keep_values(team_values_, game.team_values, manifest().team_fields.size());
    for (const protocol::event_record& r : game.records) {
        if (r.sequence <= last_record_) continue;  // resent until acknowledged: taken once
        last_record_ = r.sequence;
        ++m.game_events;
        records_.push_back(r);
        if (records_.size() > max_kept_events) records_.pop_front();
    }
}

bots::game_view client_core::seen_by_game_bot() const {
    bots::game_view seen;
    seen.own = session_.predicted();
    seen.bodies = session_.view();
    seen.player = session_.player_id();
    seen.config = session_.config();
    seen.game = &manifest();
    seen.values = &player_values_;
    seen.kind_of = [this](std::uint32_t id) -> std::uint8_t {
        const protocol::shape_desc* shape = session_.shape_of(id);
        return shape ? shape->kind : 0;
    };
    return seen;
}

std::string client_core::player_name(std::uint32_t player) const {
    const auto it = names_.find(player);
    return it == names_.end() ? std::string() : it->second;
}

void client_core::record_scoreboard() {
    outcome_.scoreboard.clear();
    outcome_.game = manifest();
    outcome_.tick_rate = session_.welcome().tick_rate;
    const std::size_t fields = outcome_.game.player_fields.size();
    const std::size_t team_fields = outcome_.game.team_fields.size();
    const protocol::match_result& result = session_.result();
    if (result.over) {
        // The Bye's own values: the final ones, whatever snapshots were lost before it.
        std::map<std::uint32_t, declared_values> final_players;
        std::map<std::uint8_t, declared_values> final_teams;
        keep_values(final_players, result.player_values, fields);
        keep_values(final_teams, result.team_values, team_fields);
        for (std::size_t i = 0; i < result.scoreboard.size(); ++i)
            outcome_.scoreboard.push_back({result.names[i], result.scoreboard[i],
                                           first_fields(final_players[result.scoreboard[i].player], fields)});
        for (const auto& [team, held] : final_teams) outcome_.teams[team] = first_fields(held, team_fields);
        outcome_.final_scoreboard = true;
        outcome_.winner = result.winner;
        outcome_.winning_team = result.winning_team;
        outcome_.winners = result.winners;
        return;
    }
    for (const auto& [id, row] : players_) {
        const auto held = player_values_.find(id);
        outcome_.scoreboard.push_back(
            {player_name(id), row,
             held == player_values_.end() ? std::vector<std::int32_t>(fields) : first_fields(held->second, fields)});
    }
    for (const auto& [team, held] : team_values_) outcome_.teams[team] = first_fields(held, team_fields);
}

void client_core::check_shapes(std::span<const protocol::BodyState> bodies) {
    if (outcome_.misbehaving) return;
    for (const protocol::BodyState& body : bodies) {
        if (shape_of(body.id()) == nullptr) ++shared_.metrics().bodies_without_shape;
    }
}

void client_core::on_pong(time_ns now) {
    // client_time is ours, echoed; a value from the future is not one we sent.
    const time_ns sent = session_.pong_time();
    if (outcome_.misbehaving || sent > now) return;
    const double rtt_ms = static_cast<double>(now - sent) / 1e6;
    shared_.metrics().rtt_ms.add(rtt_ms);
    shared_.metrics().interval_rtt_ms.add(rtt_ms);
    if (const std::optional<std::uint32_t> hold_us = session_.pong_server_hold_us()) {
        const double hold_ms = std::min(static_cast<double>(*hold_us) / 1e3, rtt_ms);
        shared_.metrics().server_hold_ms.add(hold_ms);
        shared_.metrics().network_rtt_ms.add(rtt_ms - hold_ms);
    }
}

void client_core::on_tick(std::uint64_t tick, time_ns now) {
    if (phase_ != phase::playing || close_after_flush_) return;
    ++ticks_played_;
    if (params_.mode != misbehavior::none && ticks_played_ > misbehave_after_ticks && misbehave()) return;
    if (session_.send_this_tick()) {
        // An Asteroids bot shows the others as an interpolating client does (shown_view.hpp):
        // the input about to go out, the step into the next predicted tick, carries that moment.
        const std::uint32_t next = session_.predicted_tick() + 1;
        const std::uint64_t moment = judge_hits_ ? shown_.moment(next) : 0;
        if (judge_hits_) session_.set_view_moment(moment);
        send_input(game_bot_ ? game_bot_->next(seen_by_game_bot()) : behavior_->next({session_.predicted()}));
        // The server measures the rewind from the tick the input steps from, one before.
        const std::uint64_t from = std::uint64_t{next - 1} * 256;
        if (judge_hits_)
            remember_rewind(session_.last_sequence(), static_cast<std::uint32_t>(from > moment ? from - moment : 0));
    } else
        ++shared_.metrics().inputs_left_out;
    if (phase_ == phase::ended) return;
    if (judge_hits_) claim_hits();
    // One Ping a second, cores spread over the second so the Pongs do not come in a burst.
    if ((tick + params_.index) % session_.tick_rate() == 0) append_ping(shared_.encoder(), now, pending_);
}

bool client_core::invulnerable(std::uint32_t ship, std::uint32_t tick) const {
    // After a respawn, and after the first view for the ships that joined with this player
    // (joins are not events).
    const std::uint32_t span = invulnerable_ticks();
    if (tick < first_view_tick_ + span) return true;
    const auto it = respawned_.find(ship);
    return it != respawned_.end() && tick < it->second + span;
}

void client_core::remember_rewind(std::uint32_t sequence, std::uint32_t rewind) {
    rewinds_.push_back({sequence, rewind});
    // A bullet lives 1 s and the inputs go out one a tick: a few seconds' worth is plenty.
    if (rewinds_.size() > 4u * session_.tick_rate()) rewinds_.pop_front();
}

std::uint32_t client_core::rewind_of(std::uint32_t sequence) const {
    for (auto it = rewinds_.rbegin(); it != rewinds_.rend(); ++it)
        if (it->first == sequence) return it->second;
    return shown_.delay();
}

void client_core::claim_hits() {
    const world::world_config& config = *session_.config();
    const world::real bullet_radius = rules::asteroids_params{}.bullet_radius;
    // The bullets are where the prediction has them after the last input: at the predicted tick.
    const std::uint64_t present = std::uint64_t{session_.predicted_tick()} * 256;
    for (const own_bullet& b : session_.own_bullets()) {
        if (hits_.has_claimed(b.sequence)) continue;
        // Its shooter saw the others `rewind` behind when it fired, and is shown them so for
        // the bullet's whole flight, as the server judges it (docs/LAG_COMPENSATION.md).
        const std::uint32_t rewind = rewind_of(b.sequence);
        const std::uint64_t moment = present > rewind ? present - rewind : 0;
        const auto tick = static_cast<std::uint32_t>(moment / 256);
        // The bullet's sweep over the tick that brought it here, as the server judges it.
        const world::vec2 to{b.x, b.y};
        const world::vec2 step = world::vec2{b.vx, b.vy} * config.dt;
        const world::vec2 from = to - step;
        std::uint32_t nearest = 0;
        world::real nearest_along = 2;
        for (const shown_view::shown_body& t : shown_.at(moment, config)) {
            if (t.id == session_.entity_id() || hits_.taken(t.id)) continue;
            const protocol::shape_desc* shape = session_.shape_of(t.id);
            if (shape == nullptr || (shape->kind != rules::kind_ship && shape->kind != rules::kind_rock)) continue;
            if (shape->kind == rules::kind_ship && invulnerable(t.id, tick)) continue;
            const auto along =
                rules::sweep_hits(from, step, t.position, bounding_radius(*shape) + bullet_radius, config);
            if (along && *along < nearest_along) {
                nearest_along = *along;
                nearest = t.id;
            }
        }
        if (nearest != 0) hits_.claim(b.sequence, nearest, tick);
    }
}

void client_core::send_input(const world::player_input& input) {
    protocol::input_msg message = session_.next_input(input);
    if (params_.unordered) {
        // On datagrams each Input repeats the inputs the server has not acknowledged yet (the
        // newest few): a lost one costs nothing once the next arrives.
        for (std::size_t i = 0; i < recent_count_; ++i)
            if (recent_inputs_[i].sequence > session_.last_ack()) message.earlier.push_back(recent_inputs_[i]);
        if (recent_count_ == recent_inputs_.size()) {
            std::copy(recent_inputs_.begin() + 1, recent_inputs_.end(), recent_inputs_.begin());
            --recent_count_;
        }
        recent_inputs_[recent_count_++] = {message.sequence, input.thrust, input.turn, input.buttons};
    }
    append_input(shared_.encoder(), message, pending_);
    ++shared_.metrics().inputs_sent;
    if (pending_.size() > max_pending_bytes) end(end_kind::transport_error, "server stopped reading our inputs");
}

bool client_core::misbehave() {
    switch (params_.mode) {
        case misbehavior::none:
        case misbehavior::slow_reader:  // the transport does it: reading() turns false
            return false;
        case misbehavior::flood:
            for (std::uint32_t i = 0; i < flood_inputs_per_tick && phase_ != phase::ended; ++i)
                send_input(behavior_->next({session_.predicted()}));
            return true;
        case misbehavior::garbage:
        case misbehavior::oversize:
        case misbehavior::nan:
        case misbehavior::abrupt_close:
            break;
    }
    if (fault_done_) return false;  // done once; play on until the server hangs up
    fault_done_ = true;
    switch (params_.mode) {
        case misbehavior::garbage:
            queue(garbage_frame(fault_rng_));
            return false;
        case misbehavior::oversize:
            queue(oversize_prefix());
            return false;
        case misbehavior::nan:
            send_input({std::numeric_limits<float>::quiet_NaN(), 0.0f, 0});
            return true;
        case misbehavior::abrupt_close: {
            const std::uint32_t sequence = session_.last_sequence() + 1;
            queue(half_frame(protocol::encode_input({sequence, 0.5f, 0.0f, 0})));
            close_after_flush_ = true;
            close_reason_ = "closed mid-frame on purpose (abrupt-close)";
            return true;
        }
        default:
            return false;
    }
}

void client_core::finish() {
    if (phase_ == phase::ended) return;
    if (phase_ != phase::playing)
        return end(end_kind::orderly,
                   phase_ == phase::joining ? "no Welcome before the run ended" : "not connected before the run ended");
    if (close_after_flush_) return;
    queue(protocol::encode_bye("run finished"));
    close_after_flush_ = true;
    close_reason_ = "run finished";
}

void client_core::check_join_timeout(time_ns now) {
    if (phase_ != phase::connecting && phase_ != phase::joining) return;
    if (now - launched_at_ < params_.join_timeout) return;
    end(end_kind::transport_error, phase_ == phase::connecting ? "connect timed out" : "no Welcome in time");
}

void client_core::end(end_kind kind, const std::string& reason) {
    if (phase_ == phase::ended) return;
    const bool was_playing = phase_ == phase::playing;
    phase_ = phase::ended;
    record_scoreboard();
    hits_.finish(session_.view_tick());
    outcome_.ended = true;
    outcome_.reason = reason;
    outcome_.ended_early = !shared_.stopping();
    if (kind == end_kind::protocol_error) outcome_.protocol_error = true;
    if (outcome_.ended_early) ++shared_.metrics().disconnects[reason];
    shared_.on_ended(was_playing);
}

void client_core::add_final_figures(fleet_metrics& m) const {
    if (outcome_.misbehaving) return;
    if (const predictor* p = session_.prediction()) {
        const shot_counts& shots = p->shots().counts();
        m.own_shots.exact += shots.exact;
        m.own_shots.with_error += shots.with_error;
        m.own_shots.unconfirmed += shots.unconfirmed;
        m.own_shots.unpredicted += shots.unpredicted;
    }
    m.hits.claimed += hits_.counts().claimed;
    m.hits.confirmed += hits_.counts().confirmed;
    m.hits.unclaimed_hits += hits_.counts().unclaimed_hits;
    m.hits.contested += hits_.counts().contested;
    if (snapshots_ < 2) return;
    const double seconds = static_cast<double>(last_snapshot_at_ - first_snapshot_at_) / 1e9;
    if (seconds > 0) m.snapshots_per_s_per_bot.add(static_cast<double>(snapshots_ - 1) / seconds);
}

}  // namespace arena::bots
