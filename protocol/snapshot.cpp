#include "protocol/snapshot.hpp"

#include <atomic>
#include <cmath>

#include "protocol/messages.hpp"
#include "server/world/assert.hpp"

namespace arena::protocol {
namespace {

std::atomic<std::uint64_t> replaced_total{0};

bool finite(float v) {
    return std::isfinite(v);
}

// `b` with each non-finite field written as 0; adds to `replaced` how many there were.
BodyState finite_copy(const BodyState& b, std::uint64_t& replaced) {
    const auto fix = [&replaced](float v) {
        if (finite(v)) return v;
        ++replaced;
        return 0.0f;
    };
    return {b.id(),      b.owner(),   fix(b.x()),     fix(b.y()),
            fix(b.vx()), fix(b.vy()), fix(b.angle()), fix(b.angular_velocity())};
}

// The two shape vectors, or absent ones when there is nothing to describe (the frame is then
// byte for byte what it was before shapes existed).
struct shape_offsets {
    flatbuffers::Offset<flatbuffers::Vector<const BodyShape*>> shapes;
    flatbuffers::Offset<flatbuffers::Vector<const ShapeVertex*>> vertices;
    flatbuffers::Offset<flatbuffers::Vector<const ShotOrigin*>> origins;  // absent when none
};
shape_offsets add_shapes(flatbuffers::FlatBufferBuilder& fbb, const shape_list* list) {
    if (list == nullptr || list->empty()) return {};
    shape_offsets out{fbb.CreateVectorOfStructs(list->shapes.data(), list->shapes.size()),
                      fbb.CreateVectorOfStructs(list->vertices.data(), list->vertices.size()),
                      {}};
    if (!list->origins.empty()) out.origins = fbb.CreateVectorOfStructs(list->origins.data(), list->origins.size());
    return out;
}

// The game's four vectors, absent when there is nothing to say (as for shapes).
struct game_offsets {
    flatbuffers::Offset<flatbuffers::Vector<const PlayerLine*>> players;
    flatbuffers::Offset<flatbuffers::Vector<std::uint32_t>> name_ids;
    flatbuffers::Offset<flatbuffers::Vector<flatbuffers::Offset<flatbuffers::String>>> names;
    flatbuffers::Offset<flatbuffers::Vector<const GameEvent*>> events;
    flatbuffers::Offset<flatbuffers::Vector<const GameValue*>> player_values;
    flatbuffers::Offset<flatbuffers::Vector<const GameValue*>> team_values;
    flatbuffers::Offset<flatbuffers::Vector<const GameEventRecord*>> records;
};

// A vector of `items` as the wire's structs; absent when empty.
template <class Wire, class Plain>
flatbuffers::Offset<flatbuffers::Vector<const Wire*>> wire_structs(flatbuffers::FlatBufferBuilder& fbb,
                                                                   const std::vector<Plain>& items) {
    if (items.empty()) return 0;
    std::vector<Wire> wire;
    wire.reserve(items.size());
    for (const Plain& item : items) wire.push_back(to_wire(item));
    return fbb.CreateVectorOfStructs(wire.data(), wire.size());
}
game_offsets add_game(flatbuffers::FlatBufferBuilder& fbb, const game_list* game) {
    game_offsets out;
    if (game == nullptr || game->empty()) return out;
    if (!game->players.empty()) {
        std::vector<PlayerLine> lines;
        lines.reserve(game->players.size());
        for (const player_row& r : game->players) lines.push_back(to_wire(r));
        out.players = fbb.CreateVectorOfStructs(lines.data(), lines.size());
    }
    if (!game->name_ids.empty()) {
        out.name_ids = fbb.CreateVector(game->name_ids);
        out.names = fbb.CreateVectorOfStrings(game->names);
    }
    if (!game->events.empty()) {
        std::vector<GameEvent> events;
        events.reserve(game->events.size());
        for (const game_event& e : game->events) events.push_back(to_wire(e));
        out.events = fbb.CreateVectorOfStructs(events.data(), events.size());
    }
    out.player_values = wire_structs<GameValue>(fbb, game->player_values);
    out.team_values = wire_structs<GameValue>(fbb, game->team_values);
    out.records = wire_structs<GameEventRecord>(fbb, game->records);
    return out;
}

flatbuffers::Offset<Snapshot> create_snapshot(flatbuffers::FlatBufferBuilder& fbb, std::uint32_t tick,
                                              std::uint32_t ack_sequence,
                                              flatbuffers::Offset<flatbuffers::Vector<const BodyState*>> bodies,
                                              std::uint32_t baseline_tick,
                                              flatbuffers::Offset<flatbuffers::Vector<std::uint8_t>> delta,
                                              const shape_list* shapes, const game_list* game,
                                              std::uint16_t extra_inputs_waiting = 0) {
    const shape_offsets described = add_shapes(fbb, shapes);
    const game_offsets g = add_game(fbb, game);
    return CreateSnapshot(fbb, tick, ack_sequence, bodies, baseline_tick, delta, described.shapes, described.vertices,
                          g.players, g.name_ids, g.names, g.events, described.origins, extra_inputs_waiting,
                          g.player_values, g.team_values, g.records);
}

void build_snapshot(flatbuffers::FlatBufferBuilder& fbb, std::uint32_t tick, std::uint32_t ack_sequence,
                    std::span<const BodyState> bodies, const shape_list* shapes, const game_list* game) {
    fbb.Clear();  // keeps the allocated block: no allocation once the builder is warm
    // The rare broken world: a finite copy (allocates; never on a healthy server's path).
    std::vector<BodyState> repaired;
    for (size_t i = 0; i < bodies.size(); ++i) {
        if (non_finite_field(bodies[i]) == nullptr) continue;
        std::uint64_t replaced = 0;
        repaired.assign(bodies.begin(), bodies.end());
        for (BodyState& b : repaired) b = finite_copy(b, replaced);
        replaced_total.fetch_add(replaced, std::memory_order_relaxed);
        bodies = repaired;
        break;
    }
    // One PushBytes of bodies.size() * 32 bytes, no per-body work.
    const auto body_vector = fbb.CreateVectorOfStructs(bodies.data(), bodies.size());
    finish_message(fbb, Payload::Snapshot,
                   create_snapshot(fbb, tick, ack_sequence, body_vector, 0, 0, shapes, game).Union());
}

std::span<const std::uint8_t> finished(const flatbuffers::FlatBufferBuilder& fbb) {
    return {fbb.GetBufferPointer(), fbb.GetSize()};
}

}  // namespace

const char* non_finite_field(const BodyState& b) noexcept {
    if (!finite(b.x())) return "x";
    if (!finite(b.y())) return "y";
    if (!finite(b.vx())) return "vx";
    if (!finite(b.vy())) return "vy";
    if (!finite(b.angle())) return "angle";
    if (!finite(b.angular_velocity())) return "angular_velocity";
    return nullptr;
}

std::uint64_t non_finite_values_replaced() noexcept {
    return replaced_total.load(std::memory_order_relaxed);
}

std::span<const std::uint8_t> encode_snapshot(flatbuffers::FlatBufferBuilder& fbb, std::uint32_t tick,
                                              std::uint32_t ack_sequence, std::span<const BodyState> bodies,
                                              const shape_list* shapes, const game_list* game) {
    build_snapshot(fbb, tick, ack_sequence, bodies, shapes, game);
    return finished(fbb);
}

std::span<const std::uint8_t> encode_delta_snapshot(flatbuffers::FlatBufferBuilder& fbb, std::uint32_t tick,
                                                    std::uint32_t ack_sequence, std::uint32_t baseline_tick,
                                                    std::span<const std::uint8_t> delta, const shape_list* shapes,
                                                    const game_list* game, std::uint16_t extra_inputs_waiting) {
    fbb.Clear();
    const auto bytes = fbb.CreateVector(delta.data(), delta.size());
    finish_message(
        fbb, Payload::Snapshot,
        create_snapshot(fbb, tick, ack_sequence, 0, baseline_tick, bytes, shapes, game, extra_inputs_waiting).Union());
    return finished(fbb);
}

void snapshot_encoder::build(std::uint32_t tick, std::span<const BodyState> bodies, const shape_list* shapes,
                             const game_list* game) {
    // FlatBuffers omits a field equal to its default; ack_sequence must be present in the
    // buffer to be patched in place, so force every field to be written.
    fbb_.ForceDefaults(true);
    build_snapshot(fbb_, tick, 0, bodies, shapes, game);
    built_ = true;
}

std::span<const std::uint8_t> snapshot_encoder::frame() const noexcept {
    if (!built_) return {};
    return finished(fbb_);
}

void snapshot_encoder::copy_with_ack(std::uint32_t ack_sequence, std::vector<std::uint8_t>& out) const {
    ARENA_ASSERT(built_, "copy_with_ack() before build()");
    const auto source = frame();
    out.assign(source.begin(), source.end());
    if (out.empty()) return;
    // Our own, trusted bytes: no verification needed to navigate them.
    auto* message = GetMutableSizePrefixedMessage(out.data());
    auto* snapshot = static_cast<Snapshot*>(message->mutable_payload());
    [[maybe_unused]] const bool patched = snapshot->mutate_ack_sequence(ack_sequence);
    ARENA_ASSERT(patched, "ack_sequence missing: ForceDefaults not in effect");
}

std::vector<std::uint8_t> snapshot_encoder::frame_with_ack(std::uint32_t ack_sequence) const {
    std::vector<std::uint8_t> out;
    copy_with_ack(ack_sequence, out);
    return out;
}

}  // namespace arena::protocol
