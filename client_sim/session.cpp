#include "client_sim/session.hpp"

#include <algorithm>
#include <utility>
#include <variant>

#include "protocol/config_hash.hpp"
#include "protocol/decode.hpp"
#include "protocol/verify.hpp"
#include "server/config/config_json.hpp"
#include "server/world/integrate.hpp"
#include "server/world/world.hpp"

namespace arena::bots {

namespace {

// "Reject name: reason"; a newer server may send a code we do not know: its number then.
std::string reject_text(const protocol::reject_msg& reject) {
    std::string text = "Reject ";
    const char* name = protocol::EnumNameRejectCode(reject.code);
    if (name != nullptr && *name != '\0') {
        text += name;
    } else {
        text += "code ";
        text += std::to_string(static_cast<unsigned>(reject.code));
    }
    text += ": ";
    text += reject.reason;
    return text;
}

}  // namespace

session::session(session_options options, config_source* configs)
    : options_(options), configs_(configs), frames_(protocol::max_server_frame_body) {}

protocol::Payload session::fail(std::string reason, end_kind kind) {
    if (end_ == end_kind::none) {
        error_ = std::move(reason);
        end_ = kind;
    }
    return protocol::Payload::NONE;
}

protocol::Payload session::drop() {
    stale_ = true;
    return protocol::Payload::NONE;
}

std::span<const std::uint8_t> session::keep(std::vector<std::uint8_t> frame) {
    out_ = std::move(frame);
    return out_;
}

protocol::Payload session::feed(std::span<const std::uint8_t> frame) {
    stale_ = false;
    if (ended()) return protocol::Payload::NONE;
    // Through the frame reader: it checks the prefix against the limit and gives FlatBuffers
    // the 8-byte aligned copy it wants, wherever the caller's bytes are.
    const std::size_t used = frames_.feed(frame);
    if (frames_.failed()) return fail("bad frame from the server: " + std::string(frames_.error()));
    if (!frames_.has_frame() || used != frame.size())
        return fail("a message from the server that is not exactly one frame");
    const protocol::Payload handled = handle(frames_.frame());
    frames_.next();
    return handled;
}

protocol::Payload session::handle(std::span<const std::uint8_t> frame) {
    stale_ = false;
    if (ended()) return protocol::Payload::NONE;
    const auto verified = protocol::verify_message(frame, protocol::server_frame_limits);
    if (!verified) return fail("invalid message from the server: " + verified.error);
    const protocol::Message& message = *verified.value;
    using protocol::Payload;
    const Payload type = message.payload_type();
    if (type == Payload::Welcome && !joined()) return on_welcome(message);
    if (type == Payload::Snapshot && joined()) return on_snapshot(message);
    if (type == Payload::Pong && joined()) {
        const auto pong = protocol::decode_pong(message);
        if (!pong) return fail("Pong: " + pong.error);
        pong_time_ = pong.value.client_time;
        pong_server_hold_us_ = pong.value.server_hold_us;
        return type;
    }
    if (type == Payload::Reject) return on_reject(message);
    if (type == Payload::Bye) return on_bye(message);
    if (options_.unordered && !joined() && (type == Payload::Snapshot || type == Payload::Pong))
        return drop();  // overtook the Welcome
    return fail("unexpected " + std::string(protocol::payload_name(type)) + " from the server " +
                (joined() ? "while playing" : "before Welcome"));
}

protocol::Payload session::on_welcome(const protocol::Message& message) {
    auto decoded = protocol::decode_welcome(message);
    if (!decoded) return fail("Welcome: " + decoded.error);
    const protocol::welcome_info& w = decoded.value;
    if (protocol::world_config_hash(w.world_config) != w.world_config_hash)
        return fail("Welcome: world_config_hash does not match world_config");
    if (w.world_version != world::world_version)
        return fail("Welcome: world_version " + std::to_string(w.world_version) + ", this client predicts version " +
                    std::to_string(world::world_version));
    if (w.tick_rate == 0 || w.snapshot_rate == 0) return fail("Welcome: tick_rate and snapshot_rate must be positive");
    if (configs_ != nullptr) {
        const auto shared = configs_->config_for(w);
        if (!shared) return fail("Welcome: world_config: " + shared.error);
        config_ = shared.value;
    } else {
        auto parsed = config::parse_config_json(w.world_config);
        if (!parsed) return fail("Welcome: world_config: " + parsed.error);
        config_ = &own_config_.emplace(std::move(parsed.value));
    }
    welcome_ = std::move(decoded.value);
    player_id_ = welcome_.player_id;
    entity_id_ = welcome_.entity_id;
    predictor_.emplace(*config_, entity_id_, player_id_);
    if (options_.delta_snapshots) deltas_.emplace(welcome_.tick_rate);
    return protocol::Payload::Welcome;
}

protocol::Payload session::on_snapshot(const protocol::Message& message) {
    const auto decoded = protocol::decode_snapshot(message);
    if (!decoded) return fail("Snapshot: " + decoded.error);
    const protocol::snapshot_view& snapshot = decoded.value;
    if (have_tick_ && snapshot.tick <= last_tick_) {
        if (options_.unordered) return drop();  // a duplicate, or overtaken by a newer one
        return fail("Snapshot: tick went back");
    }
    have_tick_ = true;
    last_tick_ = snapshot.tick;
    delta_problem_.clear();
    was_delta_ = snapshot.is_delta;
    delta_bytes_ = 0;
    correction_ = {};
    shot_errors_.clear();

    // Before the view: a delta that does not decode still brings its shapes and the game.
    if (!take_shapes(snapshot) || !take_game(snapshot)) return protocol::Payload::NONE;
    if (snapshot.is_delta && !deltas_) return fail("Snapshot: a delta, but this client asked for full snapshots");
    // The receiver dropped its baselines: the next Input acknowledges 0 and the server sends a
    // full view. This snapshot is skipped, the session goes on.
    if (!take_view(snapshot)) return protocol::Payload::Snapshot;
    predict(snapshot);
    if (ended()) return protocol::Payload::NONE;
    return protocol::Payload::Snapshot;
}

bool session::take_shapes(const protocol::snapshot_view& snapshot) {
    arrived_.clear();
    if (snapshot.shapes == nullptr) return true;
    const std::string problem = protocol::read_shapes(snapshot.shapes, snapshot.shape_vertices, arrived_);
    if (!problem.empty()) {
        fail("Snapshot: " + problem);
        return false;
    }
    const auto by_id = [](const protocol::shape_desc& a, const protocol::shape_desc& b) {
        return a.id < b.id;
    };
    for (const protocol::shape_desc& d : arrived_) {
        const auto at = std::lower_bound(shapes_.begin(), shapes_.end(), d, by_id);
        if (at != shapes_.end() && at->id == d.id) {
            *at = d;  // described again: it came back into view, or an ack is on its way
        } else {
            shapes_.insert(at, d);
        }
    }
    return true;
}

bool session::take_game(const protocol::snapshot_view& snapshot) {
    game_.clear();
    events_before_ = last_event_;
    if (snapshot.table == nullptr) return true;
    const std::string problem = protocol::read_game(*snapshot.table, game_);
    if (!problem.empty()) {
        fail("Snapshot: " + problem);
        return false;
    }
    // Events are resent until acknowledged: each is taken once, by its sequence.
    for (const protocol::game_event& e : game_.events) {
        if (e.sequence <= last_event_) continue;
        last_event_ = e.sequence;
        // A respawn of ours: the new ship is the own body from this snapshot on, predicted
        // like the first.
        if (e.kind == protocol::GameEventKind::respawn && e.player == player_id_) entity_id_ = e.body;
    }
    return true;
}

bool session::take_view(const protocol::snapshot_view& snapshot) {
    if (snapshot.is_delta) {
        const auto quantized = deltas_->receive(snapshot);
        if (!quantized) {
            delta_problem_ = quantized.error;
            ++delta_failures_;
            return false;
        }
        delta_bytes_ = snapshot.delta.size();
        view_.clear();
        for (const protocol::delta::quantized_body& q : quantized.value)
            view_.push_back(protocol::delta::dequantize(q));
    } else {
        view_.assign(snapshot.bodies.begin(), snapshot.bodies.end());
    }
    view_tick_ = snapshot.tick;
    view_ack_ = snapshot.ack_sequence;

    // Shapes are kept while their body is in the newest view (both lists go by id).
    std::size_t kept = 0, b = 0;
    for (std::size_t s = 0; s < shapes_.size(); ++s) {
        while (b < view_.size() && view_[b].id() < shapes_[s].id) ++b;
        if (b < view_.size() && view_[b].id() == shapes_[s].id) shapes_[kept++] = shapes_[s];
    }
    shapes_.resize(kept);
    return true;
}

void session::predict(const protocol::snapshot_view& snapshot) {
    const protocol::BodyState* own = protocol::find_body(view_, entity_id_);
    // The view and the shot origins: the own shots are predicted too (own_shots.hpp).
    correction_ = predictor_->on_snapshot(snapshot.tick, snapshot.ack_sequence, own, view_, snapshot.shot_origins);
    shot_errors_ = predictor_->take_shot_errors();
    if (correction_.problem != predictor::ack_problem::none) {
        if (options_.lenient) return;
        fail(correction_.problem == predictor::ack_problem::went_back
                 ? "Snapshot: ack_sequence went back"
                 : "Snapshot: ack_sequence acknowledges an input never sent");
        return;
    }
    last_ack_ = snapshot.ack_sequence;
    // Only delta snapshots carry the count; a full one says 0.
    if (!options_.lenient) pacer_.on_snapshot(snapshot.ack_sequence, snapshot.extra_inputs_waiting);
}

protocol::Payload session::on_reject(const protocol::Message& message) {
    auto reject = protocol::decode_reject(message);
    if (!reject) return fail("Reject: " + reject.error);
    reject_code_ = reject.value.code;
    fail(reject_text(reject.value), end_kind::by_server);
    return protocol::Payload::Reject;
}

protocol::Payload session::on_bye(const protocol::Message& message) {
    auto bye = protocol::decode_bye(message);
    if (!bye) return fail("Bye: " + bye.error);
    // An orderly goodbye (the server's match is over, or it is stopping), not a fault.
    // Swapped in member by member: the session ends here, and the code stays small (WebAssembly).
    protocol::match_result& r = bye.value.result;
    result_.over = r.over;
    result_.winner = r.winner;
    result_.scoreboard.swap(r.scoreboard);
    result_.names.swap(r.names);
    result_.player_values.swap(r.player_values);
    result_.team_values.swap(r.team_values);
    result_.winning_team = r.winning_team;
    result_.winners.swap(r.winners);
    fail("Bye: " + bye.value.reason, end_kind::by_server);
    return protocol::Payload::Bye;
}

const protocol::shape_desc* session::shape_of(std::uint32_t id) const {
    const auto dynamic = std::lower_bound(shapes_.begin(), shapes_.end(), id,
                                          [](const protocol::shape_desc& d, std::uint32_t v) { return d.id < v; });
    if (dynamic != shapes_.end() && dynamic->id == id) return &*dynamic;
    const std::vector<protocol::static_body>& statics = welcome_.statics;
    const auto fixed = std::lower_bound(statics.begin(), statics.end(), id,
                                        [](const protocol::static_body& s, std::uint32_t v) { return s.shape.id < v; });
    if (fixed != statics.end() && fixed->shape.id == id) return &fixed->shape;
    return nullptr;
}

const world::body* session::predicted() const {
    return predictor_ ? predictor_->body() : nullptr;
}

std::vector<own_bullet> session::own_bullets() const {
    std::vector<own_bullet> out;
    if (!predictor_ || config_ == nullptr) return out;
    const own_shots& shots = predictor_->shots();
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
    for (const own_shots::confirmed_shot& c : shots.confirmed()) {
        const protocol::BodyState* at = protocol::find_body(view_, c.body_id);
        if (at == nullptr) continue;
        // The view is the world after the step that took input view_ack_.
        fly(c.body_id, c.sequence, {at->x(), at->y()}, {at->vx(), at->vy()}, now - view_ack_);
    }
    // By body id (unique). An insertion sort: a few bullets, and std::sort's instantiation
    // would add about 8 KB to the WebAssembly module.
    for (std::size_t i = 1; i < out.size(); ++i)
        for (std::size_t j = i; j > 0 && out[j].body_id < out[j - 1].body_id; --j) std::swap(out[j], out[j - 1]);
    // A predicted spawn is where the bullet was before the step of the input that fired it.
    for (const predicted_shot& p : shots.waiting()) fly(0, p.sequence, p.position, p.velocity, now - p.sequence + 1);
    return out;
}

std::span<const std::uint8_t> session::hello(std::string_view name, std::string_view token, std::string_view match,
                                             std::string_view mode) {
    return keep(
        protocol::encode_hello({protocol::protocol_version, std::string(name), std::string(token),
                                options_.delta_snapshots, options_.spectator, std::string(match), std::string(mode)}));
}

bool session::send_this_tick() {
    return pacer_.send_this_tick(last_sequence() + 1);
}

protocol::input_msg session::next_input(const world::player_input& input) {
    const std::uint32_t sequence = predictor_->last_sequence() + 1;
    // The world takes only inputs that pass check_input (it asserts so): a non-finite one (a
    // misbehaving bot's, a page's bug) is predicted as no input, which the server never applies
    // either (it refuses the connection), and the sequences stay consecutive.
    const bool finite = !world::check_input(input);
    predictor_->on_input(sequence, finite ? input : world::player_input{0.0f, 0.0f, 0});
    protocol::input_msg message{sequence, input.thrust, input.turn, input.buttons, delta_ack(), {}};
    const std::uint64_t moment = view_moment_ != 0 ? view_moment_ : std::uint64_t{view_tick_} * 256;
    message.view_tick = static_cast<std::uint32_t>(moment / 256);
    message.view_fraction = static_cast<std::uint8_t>(moment % 256);
    return message;
}

std::span<const std::uint8_t> session::input(float thrust, float turn, std::uint8_t buttons) {
    if (!joined() || ended() || options_.spectator) return {};
    if (!send_this_tick()) return keep({});
    return keep(protocol::encode_input(next_input({thrust, turn, buttons})));
}

std::span<const std::uint8_t> session::ping(std::uint64_t client_time) {
    return keep(protocol::encode_ping(client_time));
}

std::span<const std::uint8_t> session::bye(std::string_view reason) {
    return keep(protocol::encode_bye(reason));
}

}  // namespace arena::bots
