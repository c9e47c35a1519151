#include "protocol/messages.hpp"

#include "protocol/version.hpp"

namespace arena::protocol {
namespace {

flatbuffers::Offset<flatbuffers::String> make_string(flatbuffers::FlatBufferBuilder& fbb, std::string_view s) {
    // An empty string_view may carry a null pointer; memcpy from null is undefined even for 0 bytes.
    return s.empty() ? fbb.CreateString("", 0) : fbb.CreateString(s.data(), s.size());
}

// Small messages: a fresh builder each, its first block sized for a typical message.
constexpr std::size_t small_message_bytes = 128;

frame_bytes to_frame(const flatbuffers::FlatBufferBuilder& fbb) {
    return frame_bytes(fbb.GetBufferPointer(), fbb.GetBufferPointer() + fbb.GetSize());
}

}  // namespace

void finish_message(flatbuffers::FlatBufferBuilder& fbb, Payload type, flatbuffers::Offset<void> payload) {
    fbb.FinishSizePrefixed(CreateMessage(fbb, type, payload), file_identifier);
}

frame_bytes encode_hello(std::uint16_t version, std::string_view name, std::string_view token, bool delta_snapshots,
                         bool spectator) {
    return encode_hello(hello_msg{version, std::string(name), std::string(token), delta_snapshots, spectator, {}, {}});
}

frame_bytes encode_hello(const hello_msg& h) {
    flatbuffers::FlatBufferBuilder fbb(small_message_bytes + h.name.size() + h.token.size() + h.match.size() +
                                       h.mode.size());
    const auto name_offset = make_string(fbb, h.name);
    const auto token_offset = make_string(fbb, h.token);
    // Absent, not empty, when unset: a Hello of today's clients keeps its bytes.
    const auto match_offset = h.match.empty() ? flatbuffers::Offset<flatbuffers::String>() : fbb.CreateString(h.match);
    const auto mode_offset = h.mode.empty() ? flatbuffers::Offset<flatbuffers::String>() : fbb.CreateString(h.mode);
    finish_message(fbb, Payload::Hello,
                   CreateHello(fbb, h.protocol_version, name_offset, token_offset, h.delta_snapshots, h.spectator,
                               match_offset, mode_offset)
                       .Union());
    return to_frame(fbb);
}

frame_bytes encode_welcome(const welcome_info& w) {
    flatbuffers::FlatBufferBuilder fbb(small_message_bytes + w.preset.size() + w.world_config.size());
    const auto preset = make_string(fbb, w.preset);
    const auto config = make_string(fbb, w.world_config);
    const auto match = w.match.empty() ? flatbuffers::Offset<flatbuffers::String>() : fbb.CreateString(w.match);
    const auto mode = w.mode.empty() ? flatbuffers::Offset<flatbuffers::String>() : fbb.CreateString(w.mode);
    // The static geometry; absent (not empty vectors) in a world without any, as before.
    flatbuffers::Offset<flatbuffers::Vector<const BodyState*>> poses;
    flatbuffers::Offset<flatbuffers::Vector<const BodyShape*>> shapes;
    flatbuffers::Offset<flatbuffers::Vector<const ShapeVertex*>> vertices;
    if (!w.statics.empty()) {
        std::vector<BodyState> states;
        shape_list list;
        states.reserve(w.statics.size());
        for (const static_body& s : w.statics) {
            states.emplace_back(s.shape.id, 0u, s.x, s.y, 0.0f, 0.0f, s.angle, 0.0f);
            list.append(s.shape);
        }
        poses = fbb.CreateVectorOfStructs(states.data(), states.size());
        shapes = fbb.CreateVectorOfStructs(list.shapes.data(), list.shapes.size());
        vertices = fbb.CreateVectorOfStructs(list.vertices.data(), list.vertices.size());
    }
    // A buffer of its own, 8-byte aligned inside the Welcome as FlatBuffers wants a nested root.
    const std::vector<std::uint8_t> manifest = encode_manifest(w.game);
    flatbuffers::Offset<flatbuffers::Vector<std::uint8_t>> game;
    if (!manifest.empty()) {
        fbb.ForceVectorAlignment(manifest.size(), sizeof(std::uint8_t), 8);
        game = fbb.CreateVector(manifest);
    }
    finish_message(
        fbb, Payload::Welcome,
        CreateWelcome(fbb, w.player_id, w.entity_id, w.tick, w.tick_rate, w.snapshot_rate, preset, config,
                      w.world_config_hash, w.world_version, w.view_radius, poses, shapes, vertices, match, mode, game)
            .Union());
    return to_frame(fbb);
}

frame_bytes encode_reject(RejectCode code, std::string_view reason) {
    flatbuffers::FlatBufferBuilder fbb(small_message_bytes + reason.size());
    const auto text = make_string(fbb, reason);
    finish_message(fbb, Payload::Reject, CreateReject(fbb, code, text).Union());
    return to_frame(fbb);
}

frame_bytes encode_input(const input_msg& in) {
    flatbuffers::FlatBufferBuilder fbb(small_message_bytes + in.earlier.size() * sizeof(EarlierInput));
    finish_message(fbb, Payload::Input, create_input(fbb, in).Union());
    return to_frame(fbb);
}

flatbuffers::Offset<Input> create_input(flatbuffers::FlatBufferBuilder& fbb, const input_msg& in) {
    flatbuffers::Offset<flatbuffers::Vector<const EarlierInput*>> earlier = 0;
    if (!in.earlier.empty()) {
        std::vector<EarlierInput> structs;
        structs.reserve(in.earlier.size());
        for (const earlier_input& e : in.earlier) structs.emplace_back(e.sequence, e.thrust, e.turn, e.buttons);
        earlier = fbb.CreateVectorOfStructs(structs);
    }
    return CreateInput(fbb, in.sequence, in.thrust, in.turn, in.buttons, in.snapshot_ack, earlier, in.view_tick,
                       in.view_fraction);
}

frame_bytes encode_ping(std::uint64_t client_time) {
    flatbuffers::FlatBufferBuilder fbb(small_message_bytes);
    finish_message(fbb, Payload::Ping, CreatePing(fbb, client_time).Union());
    return to_frame(fbb);
}

frame_bytes encode_pong(std::uint64_t client_time, std::uint32_t server_tick,
                        std::optional<std::uint32_t> server_hold_us) {
    flatbuffers::FlatBufferBuilder fbb(small_message_bytes);
    PongBuilder b(fbb);
    b.add_client_time(client_time);
    b.add_server_tick(server_tick);
    if (server_hold_us) b.add_server_hold_us(*server_hold_us);  // absent: not measured
    finish_message(fbb, Payload::Pong, b.Finish().Union());
    return to_frame(fbb);
}

frame_bytes encode_bye(std::string_view reason, const match_result* result) {
    flatbuffers::FlatBufferBuilder fbb(small_message_bytes + reason.size());
    const auto text = make_string(fbb, reason);
    if (result == nullptr || !result->over) {
        // Byte for byte the Bye of before the game's fields.
        finish_message(fbb, Payload::Bye, CreateBye(fbb, text).Union());
        return to_frame(fbb);
    }
    std::vector<PlayerLine> lines;
    for (const player_row& r : result->scoreboard) lines.push_back(to_wire(r));
    const auto board = fbb.CreateVectorOfStructs(lines.data(), lines.size());
    const auto names = fbb.CreateVectorOfStrings(result->names);
    auto values = [&fbb](const std::vector<game_value>& list) {
        std::vector<GameValue> wire;
        for (const game_value& v : list) wire.push_back(to_wire(v));
        return wire.empty() ? 0 : fbb.CreateVectorOfStructs(wire.data(), wire.size());
    };
    const auto player_values = values(result->player_values);
    const auto team_values = values(result->team_values);
    const auto winners = result->winners.empty() ? 0 : fbb.CreateVector(result->winners);
    finish_message(fbb, Payload::Bye,
                   CreateBye(fbb, text, true, result->winner, board, names, player_values, team_values,
                             result->winning_team, winners)
                       .Union());
    return to_frame(fbb);
}

}  // namespace arena::protocol
