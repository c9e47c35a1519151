#include "client_sim/client_core.hpp"

#include <algorithm>
#include <limits>

#include "client_sim/wire.hpp"
#include "protocol/config_hash.hpp"
#include "protocol/decode.hpp"
#include "protocol/verify.hpp"

namespace arena::bots {

namespace {

// A server that stops reading our inputs would make pending_ grow without end.
constexpr std::size_t max_pending_bytes = 1 << 20;

std::string reject_text(const protocol::reject_msg& reject) {
    const char* name = protocol::EnumNameRejectCode(reject.code);
    // A newer server may send a code we do not know: show its number.
    const std::string code = (name != nullptr && *name != '\0')
                                 ? std::string(name)
                                 : "code " + std::to_string(static_cast<unsigned>(reject.code));
    return code + ": " + reject.reason;
}

}  // namespace

client_core::client_core(client_shared& shared, client_params params)
    : shared_(shared),
      params_(std::move(params)),
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
    queue(protocol::encode_hello(protocol::protocol_version, params_.name, params_.token, params_.delta_snapshots));
}

void client_core::on_bytes(std::span<const std::uint8_t> data, time_ns now) {
    while (!data.empty() && phase_ != phase::ended) {
        data = data.subspan(frames_.feed(data));
        if (frames_.failed())
            return end(end_kind::protocol_error, "bad frame from the server: " + std::string(frames_.error()));
        if (frames_.has_frame()) {
            handle_frame(frames_.frame(), now);
            frames_.next();
        }
    }
}

void client_core::on_frame(std::span<const std::uint8_t> frame, time_ns now) {
    if (phase_ == phase::ended) return;
    // Through the frame reader all the same: it checks the prefix against the limit and gives
    // FlatBuffers the 8-byte aligned copy it wants.
    const std::size_t used = frames_.feed(frame);
    if (frames_.failed())
        return end(end_kind::protocol_error, "bad frame from the server: " + std::string(frames_.error()));
    if (!frames_.has_frame() || used != frame.size())
        return end(end_kind::protocol_error, "a message from the server that is not exactly one frame");
    handle_frame(frames_.frame(), now);
    frames_.next();
}

void client_core::flushed() {
    if (close_after_flush_ && pending_.empty()) end(end_kind::orderly, close_reason_);
}

void client_core::queue(std::span<const std::uint8_t> bytes) {
    pending_.insert(pending_.end(), bytes.begin(), bytes.end());
}

void client_core::handle_frame(std::span<const std::uint8_t> frame, time_ns now) {
    message_bytes_ = frame.size();
    const auto verified = protocol::verify_message(frame, protocol::server_frame_limits);
    if (!verified) return end(end_kind::protocol_error, "invalid message from the server: " + verified.error);
    const protocol::Message& message = *verified.value;
    using protocol::Payload;
    const Payload type = message.payload_type();
    if (type == Payload::Welcome && phase_ == phase::joining) return on_welcome(message);
    if (type == Payload::Snapshot && phase_ == phase::playing) return on_snapshot(message, now);
    if (type == Payload::Pong && phase_ == phase::playing) return on_pong(message, now);
    if (type == Payload::Reject) return on_reject(message);
    if (type == Payload::Bye) return on_bye(message);
    if (params_.unordered && phase_ == phase::joining && (type == Payload::Snapshot || type == Payload::Pong)) {
        ++shared_.metrics().stale_messages;  // overtook the Welcome
        return;
    }
    end(end_kind::protocol_error, "unexpected " + std::string(protocol::payload_name(type)) + " from the server " +
                                      (phase_ == phase::joining ? "before Welcome" : "while playing"));
}

void client_core::on_welcome(const protocol::Message& message) {
    const auto welcome = protocol::decode_welcome(message);
    if (!welcome) return end(end_kind::protocol_error, "Welcome: " + welcome.error);
    const protocol::welcome_info& w = welcome.value;
    if (protocol::world_config_hash(w.world_config) != w.world_config_hash)
        return end(end_kind::protocol_error, "Welcome: world_config_hash does not match world_config");
    if (w.world_version != world::world_version)
        return end(end_kind::protocol_error, "Welcome: world_version " + std::to_string(w.world_version) +
                                                 ", this client predicts version " +
                                                 std::to_string(world::world_version));
    if (w.tick_rate == 0 || w.snapshot_rate == 0)
        return end(end_kind::protocol_error, "Welcome: tick_rate and snapshot_rate must be positive");
    std::string error;
    const world::world_config* config = shared_.config_for(w, error);
    if (config == nullptr) return end(end_kind::protocol_error, "Welcome: world_config: " + error);

    player_id_ = w.player_id;
    entity_id_ = w.entity_id;
    statics_ = w.statics;
    shapes_.clear();
    tick_rate_ = w.tick_rate;
    predictor_.emplace(*config, entity_id_, player_id_);
    if (params_.delta_snapshots) deltas_.emplace(tick_rate_);
    behavior_.emplace(params_.kind, params_.seed, params_.index, *config);
    phase_ = phase::playing;
    outcome_.joined = true;
    shared_.on_joined(w);
}

void client_core::on_snapshot(const protocol::Message& message, time_ns now) {
    const auto decoded = protocol::decode_snapshot(message);
    if (!decoded) return end(end_kind::protocol_error, "Snapshot: " + decoded.error);
    const protocol::snapshot_view& snapshot = decoded.value;
    fleet_metrics& m = shared_.metrics();
    if (params_.unordered && snapshots_ > 0 && snapshot.tick <= last_snapshot_tick_) {
        ++m.stale_messages;  // a duplicate, or overtaken by a newer one
        return;
    }
    last_snapshot_tick_ = snapshot.tick;
    ++m.snapshots;
    ++m.interval_snapshots;
    if (snapshots_++ == 0) {
        first_snapshot_at_ = now;
    } else if (!outcome_.misbehaving) {
        m.snapshot_gap_ms.add(static_cast<double>(now - last_snapshot_at_) / 1e6);
    }
    last_snapshot_at_ = now;
    m.snapshot_bytes_each.add(static_cast<double>(message_bytes_));
    m.snapshot_bytes += message_bytes_;

    // Before the view: a delta that does not decode still brings its shapes and the game.
    if (!take_shapes(snapshot) || !take_game(snapshot)) return;
    std::span<const protocol::BodyState> bodies = snapshot.bodies;
    if (snapshot.is_delta) {
        if (!deltas_) return end(end_kind::protocol_error, "Snapshot: a delta, but this bot asked for full snapshots");
        ++m.delta_snapshots;
        const auto view = deltas_->receive(snapshot);
        if (!view) {
            // The receiver dropped its baselines, so the next ack (0) brings a full view.
            ++m.delta_errors;
            ++m.delta_problems[view.error];
            return;
        }
        m.delta_payload_bytes += snapshot.delta.size();
        m.delta_bodies += view.value.size();
        decoded_.clear();
        for (const protocol::delta::quantized_body& q : view.value) decoded_.push_back(protocol::delta::dequantize(q));
        bodies = decoded_;
    }
    m.bodies_in_view.add(static_cast<double>(bodies.size()));
    m.view_bodies += bodies.size();
    check_shapes(bodies);

    const protocol::BodyState* own = protocol::find_body(bodies, entity_id_);
    const predictor::correction c =
        predictor_->on_snapshot(snapshot.tick, snapshot.ack_sequence, own, bodies, snapshot.shot_origins);
    if (c.problem != predictor::ack_problem::none && !outcome_.misbehaving) {
        return end(end_kind::protocol_error, c.problem == predictor::ack_problem::went_back
                                                 ? "Snapshot: ack_sequence went back"
                                                 : "Snapshot: ack_sequence acknowledges an input never sent");
    }
    if (c.problem == predictor::ack_problem::none) last_ack_ = snapshot.ack_sequence;
    if (!outcome_.misbehaving) {
        if (c.error) {
            m.prediction_error_m.add(*c.error);
            if (*c.error == 0.0f) ++m.predictions_exact;
            m.interval_prediction_error_m.add(*c.error);
        }
        m.input_lag_ticks.add(static_cast<double>(predictor_->last_sequence() - snapshot.ack_sequence));
        pacer_.on_snapshot(snapshot.ack_sequence, snapshot.extra_inputs_waiting);
        for (const float e : predictor_->take_shot_errors()) m.own_shot_error_m.add(e);
    }
    behavior_->observe(bodies, entity_id_);
}

bool client_core::take_shapes(const protocol::snapshot_view& snapshot) {
    if (snapshot.shapes == nullptr) return true;
    arrived_.clear();
    const std::string problem = protocol::read_shapes(snapshot.shapes, snapshot.shape_vertices, arrived_);
    if (!problem.empty()) {
        end(end_kind::protocol_error, "Snapshot: " + problem);
        return false;
    }
    fleet_metrics& m = shared_.metrics();
    m.shapes_received += arrived_.size();
    m.shape_bytes += arrived_.size() * sizeof(protocol::BodyShape);
    const auto by_id = [](const protocol::shape_desc& a, const protocol::shape_desc& b) {
        return a.id < b.id;
    };
    for (const protocol::shape_desc& d : arrived_) {
        m.shape_bytes += d.vertex_count * sizeof(protocol::ShapeVertex);
        const auto at = std::lower_bound(shapes_.begin(), shapes_.end(), d, by_id);
        if (at != shapes_.end() && at->id == d.id) {
            *at = d;  // described again: it came back into view, or an ack is on its way
        } else {
            shapes_.insert(at, d);
        }
    }
    return true;
}

bool client_core::take_game(const protocol::snapshot_view& snapshot) {
    if (snapshot.table == nullptr) return true;
    game_.clear();
    const std::string problem = protocol::read_game(*snapshot.table, game_);
    if (!problem.empty()) {
        end(end_kind::protocol_error, problem);
        return false;
    }
    if (game_.empty()) return true;
    fleet_metrics& m = shared_.metrics();
    m.game_bytes += game_.wire_bytes();
    for (std::size_t i = 0; i < game_.name_ids.size(); ++i) names_[game_.name_ids[i]] = game_.names[i];
    for (const protocol::player_row& row : game_.players) players_[row.player] = row;
    for (const protocol::game_event& e : game_.events) {
        if (e.sequence <= last_event_) continue;  // taken from an earlier snapshot
        last_event_ = e.sequence;
        ++m.game_events;
        // A respawn of ours: the new ship is our body from this snapshot on.
        if (e.kind == protocol::GameEventKind::respawn && e.player == player_id_) entity_id_ = e.body;
        events_.push_back(e);
        if (events_.size() > max_kept_events) events_.pop_front();
    }
    return true;
}

std::string client_core::player_name(std::uint32_t player) const {
    const auto it = names_.find(player);
    return it == names_.end() ? std::string() : it->second;
}

void client_core::record_scoreboard() {
    outcome_.scoreboard.clear();
    if (result_.over) {
        for (std::size_t i = 0; i < result_.scoreboard.size(); ++i)
            outcome_.scoreboard.push_back({result_.names[i], result_.scoreboard[i]});
        outcome_.final_scoreboard = true;
        outcome_.winner = result_.winner;
        return;
    }
    for (const auto& [id, row] : players_) outcome_.scoreboard.push_back({player_name(id), row});
}

void client_core::check_shapes(std::span<const protocol::BodyState> bodies) {
    // Both lists go by id: one merge keeps the shapes of the view's bodies.
    std::size_t keep = 0, b = 0;
    for (std::size_t s = 0; s < shapes_.size(); ++s) {
        while (b < bodies.size() && bodies[b].id() < shapes_[s].id) ++b;
        if (b < bodies.size() && bodies[b].id() == shapes_[s].id) shapes_[keep++] = shapes_[s];
    }
    shapes_.resize(keep);
    if (outcome_.misbehaving) return;
    for (const protocol::BodyState& body : bodies) {
        if (shape_of(body.id()) == nullptr) ++shared_.metrics().bodies_without_shape;
    }
}

const protocol::shape_desc* client_core::shape_of(std::uint32_t id) const {
    const auto dynamic = std::lower_bound(shapes_.begin(), shapes_.end(), id,
                                          [](const protocol::shape_desc& d, std::uint32_t v) { return d.id < v; });
    if (dynamic != shapes_.end() && dynamic->id == id) return &*dynamic;
    const auto fixed = std::lower_bound(statics_.begin(), statics_.end(), id,
                                        [](const protocol::static_body& s, std::uint32_t v) { return s.shape.id < v; });
    if (fixed != statics_.end() && fixed->shape.id == id) return &fixed->shape;
    return nullptr;
}

void client_core::on_pong(const protocol::Message& message, time_ns now) {
    const auto pong = protocol::decode_pong(message);
    if (!pong) return end(end_kind::protocol_error, "Pong: " + pong.error);
    // client_time is ours, echoed; a value from the future is not one we sent.
    if (outcome_.misbehaving || pong.value.client_time > now) return;
    const double rtt_ms = static_cast<double>(now - pong.value.client_time) / 1e6;
    shared_.metrics().rtt_ms.add(rtt_ms);
    shared_.metrics().interval_rtt_ms.add(rtt_ms);
    if (pong.value.server_hold_us) {
        const double hold_ms = std::min(static_cast<double>(*pong.value.server_hold_us) / 1e3, rtt_ms);
        shared_.metrics().server_hold_ms.add(hold_ms);
        shared_.metrics().network_rtt_ms.add(rtt_ms - hold_ms);
    }
}

void client_core::on_reject(const protocol::Message& message) {
    const auto reject = protocol::decode_reject(message);
    if (!reject) return end(end_kind::protocol_error, "Reject: " + reject.error);
    const std::string text = reject_text(reject.value);
    ++shared_.metrics().rejects[text];
    outcome_.server_goodbye = reject.value.code == protocol::RejectCode::shutting_down;
    end(end_kind::by_server, "Reject " + text);
}

void client_core::on_bye(const protocol::Message& message) {
    const auto bye = protocol::decode_bye(message);
    if (!bye) return end(end_kind::protocol_error, "Bye: " + bye.error);
    // An orderly goodbye (the server's match is over, or it is stopping), not a fault.
    outcome_.server_goodbye = true;
    result_ = bye.value.result;
    end(end_kind::by_server, "Bye: " + bye.value.reason);
}

void client_core::on_tick(std::uint64_t tick, time_ns now) {
    if (phase_ != phase::playing || close_after_flush_) return;
    ++ticks_played_;
    if (params_.mode != misbehavior::none && ticks_played_ > misbehave_after_ticks && misbehave()) return;
    if (pacer_.send_this_tick(predictor_->last_sequence() + 1))
        send_input(behavior_->next({predictor_->body()}));
    else
        ++shared_.metrics().inputs_left_out;
    if (phase_ == phase::ended) return;
    // One Ping a second, cores spread over the second so the Pongs do not come in a burst.
    if ((tick + params_.index) % tick_rate_ == 0) append_ping(shared_.encoder(), now, pending_);
}

void client_core::send_input(const world::player_input& input) {
    const std::uint32_t sequence = predictor_->last_sequence() + 1;
    // A NaN input goes to the predictor too (the world skips inputs that fail check_input),
    // so that sequences stay consecutive.
    predictor_->on_input(sequence, input);
    const std::uint32_t snapshot_ack = deltas_ ? deltas_->ack() : 0;
    protocol::input_msg message{sequence, input.thrust, input.turn, input.buttons, snapshot_ack, {}};
    if (params_.unordered) {
        // On datagrams each Input repeats the inputs the server has not acknowledged yet (the
        // newest few): a lost one costs nothing once the next arrives.
        for (const protocol::earlier_input& e : recent_inputs_)
            if (e.sequence > last_ack_) message.earlier.push_back(e);
        if (recent_inputs_.size() == protocol::max_earlier_inputs) recent_inputs_.pop_front();
        recent_inputs_.push_back({sequence, input.thrust, input.turn, input.buttons});
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
                send_input(behavior_->next({predictor_->body()}));
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
            const std::uint32_t sequence = predictor_->last_sequence() + 1;
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
    outcome_.ended = true;
    outcome_.reason = reason;
    outcome_.ended_early = !shared_.stopping();
    if (kind == end_kind::protocol_error) outcome_.protocol_error = true;
    if (outcome_.ended_early) ++shared_.metrics().disconnects[reason];
    shared_.on_ended(was_playing);
}

void client_core::add_final_figures(fleet_metrics& m) const {
    if (outcome_.misbehaving) return;
    if (predictor_) {
        const shot_counts& shots = predictor_->shots().counts();
        m.own_shots.exact += shots.exact;
        m.own_shots.with_error += shots.with_error;
        m.own_shots.unconfirmed += shots.unconfirmed;
        m.own_shots.unpredicted += shots.unpredicted;
    }
    if (snapshots_ < 2) return;
    const double seconds = static_cast<double>(last_snapshot_at_ - first_snapshot_at_) / 1e9;
    if (seconds > 0) m.snapshots_per_s_per_bot.add(static_cast<double>(snapshots_ - 1) / seconds);
}

}  // namespace arena::bots
