#include "protocol/decode.hpp"

#include "protocol/snapshot.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace arena::protocol {
namespace {

std::string to_string(const flatbuffers::String* s) {
    return s == nullptr ? std::string() : s->str();
}

// The reason for a message of the wrong type (payload_as<T>() returned null).
std::string unexpected(const Message& message, Payload wanted) {
    return "expected " + std::string(payload_name(wanted)) + ", got " +
           std::string(payload_name(message.payload_type()));
}

}  // namespace

std::string_view payload_name(Payload type) noexcept {
    const auto v = static_cast<std::uint8_t>(type);
    if (v > static_cast<std::uint8_t>(Payload::MAX)) return "unknown";
    return EnumNamePayload(type);
}

result<hello_msg> decode_hello(const Message& message) {
    const auto* t = message.payload_as<Hello>();
    if (t == nullptr) return result<hello_msg>::failure(unexpected(message, Payload::Hello));
    return result<hello_msg>::success({t->protocol_version(), to_string(t->name()), to_string(t->token()),
                                       t->delta_snapshots(), t->spectator(), to_string(t->match()),
                                       to_string(t->mode())});
}

result<welcome_info> decode_welcome(const Message& message) {
    const auto* t = message.payload_as<Welcome>();
    if (t == nullptr) return result<welcome_info>::failure(unexpected(message, Payload::Welcome));
    welcome_info w;
    w.player_id = t->player_id();
    w.entity_id = t->entity_id();
    w.tick = t->tick();
    w.tick_rate = t->tick_rate();
    w.snapshot_rate = t->snapshot_rate();
    w.preset = to_string(t->preset());
    w.world_config = to_string(t->world_config());
    w.world_config_hash = t->world_config_hash();
    w.world_version = t->world_version();
    w.view_radius = t->view_radius();
    w.match = to_string(t->match());
    w.mode = to_string(t->mode());
    if (const auto* game = t->game()) {
        auto manifest = decode_manifest({game->data(), game->size()});
        if (!manifest.ok()) return result<welcome_info>::failure("Welcome.game: " + manifest.error);
        w.game = std::move(manifest.value);
    }
    // The static geometry: one pose per shape, the same ids, finite poses.
    std::vector<shape_desc> shapes;
    const std::string problem = read_shapes(t->static_shapes(), t->static_vertices(), shapes);
    if (!problem.empty()) return result<welcome_info>::failure("Welcome.static_shapes: " + problem);
    const auto* poses = t->static_bodies();
    const std::size_t pose_count = poses == nullptr ? 0 : poses->size();
    if (pose_count != shapes.size()) {
        return result<welcome_info>::failure("Welcome: " + std::to_string(pose_count) + " static_bodies but " +
                                             std::to_string(shapes.size()) + " static_shapes");
    }
    w.statics.reserve(shapes.size());
    for (std::size_t i = 0; i < shapes.size(); ++i) {
        const BodyState& pose = *poses->Get(static_cast<flatbuffers::uoffset_t>(i));
        if (pose.id() != shapes[i].id) {
            return result<welcome_info>::failure("Welcome: static_bodies[" + std::to_string(i) + "] is body " +
                                                 std::to_string(pose.id()) + ", its shape is body " +
                                                 std::to_string(shapes[i].id));
        }
        if (const char* field = non_finite_field(pose)) {
            return result<welcome_info>::failure("Welcome: static_bodies[" + std::to_string(i) + "]." + field +
                                                 " is not finite");
        }
        w.statics.push_back({pose.x(), pose.y(), pose.angle(), shapes[i]});
    }
    return result<welcome_info>::success(std::move(w));
}

result<reject_msg> decode_reject(const Message& message) {
    const auto* t = message.payload_as<Reject>();
    if (t == nullptr) return result<reject_msg>::failure(unexpected(message, Payload::Reject));
    // An unknown code (from a newer server) is kept as is: the reason text still explains it.
    return result<reject_msg>::success({t->code(), to_string(t->reason())});
}

result<input_msg> decode_input(const Message& message) {
    const auto* t = message.payload_as<Input>();
    if (t == nullptr) return result<input_msg>::failure(unexpected(message, Payload::Input));
    input_msg in{t->sequence(),     t->thrust(), t->turn(),      t->buttons(),
                 t->snapshot_ack(), {},          t->view_tick(), t->view_fraction()};
    // Whether the numbers are finite is admission's question (world::check_input), asked once
    // for the Input and its earlier list: the decoder reads the structure.
    if (const auto* earlier = t->earlier()) {
        if (earlier->size() > max_earlier_inputs)
            return result<input_msg>::failure("Input.earlier holds " + std::to_string(earlier->size()) +
                                              " inputs, more than " + std::to_string(max_earlier_inputs));
        in.earlier.reserve(earlier->size());
        std::uint32_t previous = 0;
        for (const EarlierInput* e : *earlier) {
            if (e->sequence() <= previous || e->sequence() >= in.sequence)
                return result<input_msg>::failure("Input.earlier: sequences must rise and stay below the Input's own");
            previous = e->sequence();
            in.earlier.push_back({e->sequence(), e->thrust(), e->turn(), e->buttons()});
        }
    }
    return result<input_msg>::success(std::move(in));
}

result<ping_msg> decode_ping(const Message& message) {
    const auto* t = message.payload_as<Ping>();
    if (t == nullptr) return result<ping_msg>::failure(unexpected(message, Payload::Ping));
    return result<ping_msg>::success({t->client_time()});
}

result<pong_msg> decode_pong(const Message& message) {
    const auto* t = message.payload_as<Pong>();
    if (t == nullptr) return result<pong_msg>::failure(unexpected(message, Payload::Pong));
    pong_msg pong{t->client_time(), t->server_tick()};
    if (const auto hold = t->server_hold_us(); hold.has_value()) pong.server_hold_us = *hold;
    return result<pong_msg>::success(pong);
}

result<bye_msg> decode_bye(const Message& message) {
    const auto* t = message.payload_as<Bye>();
    if (t == nullptr) return result<bye_msg>::failure(unexpected(message, Payload::Bye));
    bye_msg bye{to_string(t->reason())};
    if (!t->match_over()) return result<bye_msg>::success(std::move(bye));
    match_result& r = bye.result;
    r.over = true;
    r.winner = t->winner();
    const std::size_t lines = t->scoreboard() == nullptr ? 0 : t->scoreboard()->size();
    const std::size_t names = t->scoreboard_names() == nullptr ? 0 : t->scoreboard_names()->size();
    if (lines != names)
        return result<bye_msg>::failure("Bye: " + std::to_string(lines) + " scoreboard lines for " +
                                        std::to_string(names) + " scoreboard_names");
    for (std::size_t i = 0; i < lines; ++i) {
        const auto k = static_cast<flatbuffers::uoffset_t>(i);
        r.scoreboard.push_back(from_wire(*t->scoreboard()->Get(k)));
        r.names.push_back(t->scoreboard_names()->Get(k)->str());
    }
    if (const auto* values = t->player_values())
        for (const GameValue* v : *values) r.player_values.push_back(from_wire(*v));
    if (const auto* values = t->team_values())
        for (const GameValue* v : *values) r.team_values.push_back(from_wire(*v));
    r.winning_team = t->winning_team();
    if (const auto* winners = t->winners()) r.winners.assign(winners->begin(), winners->end());
    return result<bye_msg>::success(std::move(bye));
}

result<snapshot_view> decode_snapshot(const Message& message) {
    const auto* t = message.payload_as<Snapshot>();
    if (t == nullptr) return result<snapshot_view>::failure(unexpected(message, Payload::Snapshot));
    snapshot_view view{
        t->tick(), t->ack_sequence(),        {}, t->baseline_tick(), {}, false, t->shapes(), t->shape_vertices(), t,
        {},        t->extra_inputs_waiting()};
    if (const auto* delta = t->delta(); delta != nullptr) {
        view.is_delta = true;
        view.delta = {delta->data(), delta->size()};
    }
    if (const auto* bodies = t->bodies(); bodies != nullptr && bodies->size() > 0) {
        // The Verifier checked the vector lies inside the frame, 4-byte aligned as BodyState
        // requires; structs are stored exactly as the C++ type lays them out.
        view.bodies = {reinterpret_cast<const BodyState*>(bodies->Data()), bodies->size()};
        // A server never sends NaN or an infinity (snapshot.cpp); one that does is broken, and a
        // client must not predict from it.
        for (const BodyState& b : view.bodies) {
            if (const char* field = non_finite_field(b))
                return result<snapshot_view>::failure("body " + std::to_string(b.id()) + " has a non-finite " + field);
        }
    }
    if (const auto* origins = t->shot_origins(); origins != nullptr && origins->size() > 0) {
        view.shot_origins = {reinterpret_cast<const ShotOrigin*>(origins->Data()), origins->size()};
        for (const ShotOrigin& o : view.shot_origins) {
            for (const float v : {o.x(), o.y(), o.vx(), o.vy()}) {
                if (!std::isfinite(v))
                    return result<snapshot_view>::failure("the shot origin of body " + std::to_string(o.body_id()) +
                                                          " is not finite");
            }
        }
    }
    return result<snapshot_view>::success(view);
}

const BodyState* find_body(std::span<const BodyState> bodies, std::uint32_t id) {
    const auto at = std::lower_bound(bodies.begin(), bodies.end(), id,
                                     [](const BodyState& b, std::uint32_t v) { return b.id() < v; });
    return at != bodies.end() && at->id() == id ? &*at : nullptr;
}

}  // namespace arena::protocol
