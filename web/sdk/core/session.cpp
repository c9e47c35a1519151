#include "web/sdk/core/session.hpp"

#include <algorithm>
#include <variant>

#include "protocol/config_hash.hpp"
#include "protocol/decode.hpp"
#include "protocol/messages.hpp"
#include "protocol/verify.hpp"
#include "server/config/config_json.hpp"
#include "server/world/integrate.hpp"
#include "server/world/world.hpp"

namespace arena::sdk {

session::session(bool delta_snapshots, bool spectator)
    : delta_snapshots_(delta_snapshots), spectator_(spectator), frames_(protocol::max_server_frame_body) {}

protocol::Payload session::fail(std::string reason) {
    if (!ended_) error_ = std::move(reason);
    ended_ = true;
    return protocol::Payload::NONE;
}

std::span<const std::uint8_t> session::keep(std::vector<std::uint8_t> frame) {
    out_ = std::move(frame);
    return out_;
}

protocol::Payload session::feed(std::span<const std::uint8_t> frame) {
    if (ended_) return protocol::Payload::NONE;
    // Through the frame reader: it checks the prefix against the limit and gives FlatBuffers
    // the 8-byte aligned copy it wants, wherever the caller's bytes are.
    const std::size_t used = frames_.feed(frame);
    if (frames_.failed()) return fail("bad frame from the server: " + std::string(frames_.error()));
    if (!frames_.has_frame() || used != frame.size())
        return fail("a message from the server that is not exactly one frame");
    const auto verified = protocol::verify_message(frames_.frame(), protocol::server_frame_limits);
    if (!verified) {
        frames_.next();
        return fail("invalid message from the server: " + verified.error);
    }
    const protocol::Message& message = *verified.value;
    using protocol::Payload;
    const Payload type = message.payload_type();
    Payload handled = type;
    if (type == Payload::Welcome && !joined()) {
        handled = on_welcome(message);
    } else if (type == Payload::Snapshot && joined()) {
        handled = on_snapshot(message);
    } else if (type == Payload::Pong && joined()) {
        if (!protocol::decode_pong(message)) handled = fail("Pong: malformed");
    } else if (type == Payload::Reject) {
        const auto reject = protocol::decode_reject(message);
        if (!reject) {
            handled = fail("Reject: " + reject.error);
        } else {
            const char* name = protocol::EnumNameRejectCode(reject.value.code);
            fail("Reject " + std::string(name != nullptr && *name != '\0' ? name : "unknown") + ": " +
                 reject.value.reason);
        }
    } else if (type == Payload::Bye) {
        const auto bye = protocol::decode_bye(message);
        if (!bye) {
            handled = fail("Bye: " + bye.error);
        } else {
            fail("Bye: " + bye.value.reason);
        }
    } else {
        handled = fail("unexpected " + std::string(protocol::payload_name(type)) + " from the server " +
                       (joined() ? "while playing" : "before Welcome"));
    }
    frames_.next();
    return handled;
}

protocol::Payload session::on_welcome(const protocol::Message& message) {
    const auto welcome = protocol::decode_welcome(message);
    if (!welcome) return fail("Welcome: " + welcome.error);
    const protocol::welcome_info& w = welcome.value;
    if (protocol::world_config_hash(w.world_config) != w.world_config_hash)
        return fail("Welcome: world_config_hash does not match world_config");
    if (w.world_version != world::world_version)
        return fail("Welcome: world_version " + std::to_string(w.world_version) + ", this client predicts version " +
                    std::to_string(world::world_version));
    if (w.tick_rate == 0 || w.snapshot_rate == 0) return fail("Welcome: tick_rate and snapshot_rate must be positive");
    auto parsed = config::parse_config_json(w.world_config);
    if (auto* e = std::get_if<config::config_error>(&parsed)) return fail("Welcome: world_config: " + e->message);
    config_ = std::get<world::world_config>(std::move(parsed));
    player_id_ = w.player_id;
    entity_id_ = w.entity_id;
    tick_rate_ = w.tick_rate;
    snapshot_rate_ = w.snapshot_rate;
    statics_ = w.statics;
    predictor_.emplace(*config_, entity_id_, player_id_);
    if (delta_snapshots_) deltas_.emplace(tick_rate_);
    return protocol::Payload::Welcome;
}

protocol::Payload session::on_snapshot(const protocol::Message& message) {
    const auto decoded = protocol::decode_snapshot(message);
    if (!decoded) return fail("Snapshot: " + decoded.error);
    const protocol::snapshot_view& snapshot = decoded.value;
    if (have_view_ && snapshot.tick <= view_tick_) return fail("Snapshot: tick went back");
    delta_problem_.clear();

    // The shapes first: a delta that does not decode still brings them.
    if (snapshot.shapes != nullptr) {
        arrived_.clear();
        const std::string problem = protocol::read_shapes(snapshot.shapes, snapshot.shape_vertices, arrived_);
        if (!problem.empty()) return fail("Snapshot: " + problem);
        const auto by_id = [](const protocol::shape_desc& a, const protocol::shape_desc& b) {
            return a.id < b.id;
        };
        for (const protocol::shape_desc& d : arrived_) {
            const auto at = std::lower_bound(shapes_.begin(), shapes_.end(), d, by_id);
            if (at != shapes_.end() && at->id == d.id) {
                *at = d;
            } else {
                shapes_.insert(at, d);
            }
        }
    }

    if (snapshot.is_delta) {
        if (!deltas_) return fail("Snapshot: a delta, but this client asked for full snapshots");
        const auto quantized = deltas_->receive(snapshot);
        // The receiver dropped its baselines: the next Input acknowledges 0 and the server
        // sends a full view. This snapshot is skipped, the session goes on.
        if (!quantized) {
            delta_problem_ = quantized.error;
            ++delta_failures_;
            return protocol::Payload::Snapshot;
        }
        view_.clear();
        for (const protocol::delta::quantized_body& q : quantized.value)
            view_.push_back(protocol::delta::dequantize(q));
    } else {
        view_.assign(snapshot.bodies.begin(), snapshot.bodies.end());
    }
    have_view_ = true;
    view_tick_ = snapshot.tick;
    view_ack_ = snapshot.ack_sequence;

    // Shapes are kept while their body is in the newest view (both lists go by id).
    std::size_t kept = 0, b = 0;
    for (std::size_t s = 0; s < shapes_.size(); ++s) {
        while (b < view_.size() && view_[b].id() < shapes_[s].id) ++b;
        if (b < view_.size() && view_[b].id() == shapes_[s].id) shapes_[kept++] = shapes_[s];
    }
    shapes_.resize(kept);

    // A respawn of ours (GameEvent respawn): the new ship is the own body from this snapshot
    // on, predicted like the first (as client_sim/client_core.cpp follows it). Events are resent
    // until acknowledged: each is taken once, by its sequence.
    if (snapshot.table != nullptr) {
        game_.clear();
        const std::string problem = protocol::read_game(*snapshot.table, game_);
        if (!problem.empty()) return fail("Snapshot: " + problem);
        for (const protocol::game_event& e : game_.events) {
            if (e.sequence <= last_event_) continue;
            last_event_ = e.sequence;
            if (e.kind == protocol::GameEventKind::respawn && e.player == player_id_) entity_id_ = e.body;
        }
    }

    const protocol::BodyState* own = protocol::find_body(view_, entity_id_);
    // The view and the shot origins: the own shots are predicted too (own_shots.hpp).
    const bots::predictor::correction c =
        predictor_->on_snapshot(snapshot.tick, snapshot.ack_sequence, own, view_, snapshot.shot_origins);
    if (c.problem == bots::predictor::ack_problem::went_back) return fail("Snapshot: ack_sequence went back");
    if (c.problem == bots::predictor::ack_problem::ahead)
        return fail("Snapshot: ack_sequence acknowledges an input never sent");
    prediction_error_ = c.error;
    // Only delta snapshots carry the count; a full one says 0.
    pacer_.on_snapshot(snapshot.ack_sequence, snapshot.extra_inputs_waiting);
    return protocol::Payload::Snapshot;
}

const world::body* session::predicted() const {
    return predictor_ ? predictor_->body() : nullptr;
}

std::vector<own_bullet> session::own_bullets() const {
    std::vector<own_bullet> out;
    if (!predictor_ || !config_) return out;
    const bots::own_shots& shots = predictor_->shots();
    const std::uint32_t now = predictor_->last_sequence();
    // The world's steps of a free body: x += v·Δt, then back into a wrapping world.
    const auto fly = [&](std::uint32_t body_id, std::uint32_t sequence, world::vec2 at, world::vec2 velocity,
                         std::uint32_t steps) {
        world::body b;
        b.position = at;
        b.velocity = velocity;
        for (std::uint32_t k = 0; k < steps; ++k) {
            world::integrate_position(b, config_->dt);
            world::wrap_position(b, *config_);
        }
        out.push_back({body_id, sequence, b.position.x(), b.position.y(), b.velocity.x(), b.velocity.y()});
    };
    for (const bots::own_shots::confirmed_shot& c : shots.confirmed()) {
        const protocol::BodyState* at = protocol::find_body(view_, c.body_id);
        if (at == nullptr) continue;
        // The view is the world after the step that took input view_ack_.
        fly(c.body_id, c.sequence, {at->x(), at->y()}, {at->vx(), at->vy()}, now - view_ack_);
    }
    std::sort(out.begin(), out.end(), [](const own_bullet& a, const own_bullet& b) { return a.body_id < b.body_id; });
    // A predicted spawn is where the bullet was before the step of the input that fired it.
    for (const bots::predicted_shot& p : shots.waiting())
        fly(0, p.sequence, p.position, p.velocity, now - p.sequence + 1);
    return out;
}

std::span<const std::uint8_t> session::hello(std::string_view name, std::string_view token) {
    return keep(protocol::encode_hello(protocol::protocol_version, name, token, delta_snapshots_, spectator_));
}

std::span<const std::uint8_t> session::input(float thrust, float turn, std::uint8_t buttons) {
    if (!predictor_ || ended_ || spectator_) return {};
    const std::uint32_t sequence = predictor_->last_sequence() + 1;
    if (!pacer_.send_this_tick(sequence)) return keep({});
    const world::player_input in{thrust, turn, buttons};
    predictor_->on_input(sequence, in);
    return keep(protocol::encode_input({sequence, thrust, turn, buttons, delta_ack(), {}}));
}

std::span<const std::uint8_t> session::ping(std::uint64_t client_time) {
    return keep(protocol::encode_ping(client_time));
}

std::span<const std::uint8_t> session::bye(std::string_view reason) {
    return keep(protocol::encode_bye(reason));
}

}  // namespace arena::sdk
