#include "protocol/snapshot.hpp"

#include <cassert>

#include "protocol/messages.hpp"

namespace arena::protocol {
namespace {

void build_snapshot(flatbuffers::FlatBufferBuilder& fbb, std::uint32_t tick, std::uint32_t ack_sequence,
                    std::span<const BodyState> bodies) {
    fbb.Clear();  // keeps the allocated block: no allocation once the builder is warm
    // One PushBytes of bodies.size() * 32 bytes, no per-body work.
    const auto body_vector = fbb.CreateVectorOfStructs(bodies.data(), bodies.size());
    finish_message(fbb, Payload::Snapshot, CreateSnapshot(fbb, tick, ack_sequence, body_vector).Union());
}

std::span<const std::uint8_t> finished(const flatbuffers::FlatBufferBuilder& fbb) {
    return {fbb.GetBufferPointer(), fbb.GetSize()};
}

}  // namespace

std::span<const std::uint8_t> encode_snapshot(flatbuffers::FlatBufferBuilder& fbb, std::uint32_t tick,
                                              std::uint32_t ack_sequence, std::span<const BodyState> bodies) {
    build_snapshot(fbb, tick, ack_sequence, bodies);
    return finished(fbb);
}

std::span<const std::uint8_t> encode_delta_snapshot(flatbuffers::FlatBufferBuilder& fbb, std::uint32_t tick,
                                                    std::uint32_t ack_sequence, std::uint32_t baseline_tick,
                                                    std::span<const std::uint8_t> delta) {
    fbb.Clear();
    const auto bytes = fbb.CreateVector(delta.data(), delta.size());
    finish_message(fbb, Payload::Snapshot, CreateSnapshot(fbb, tick, ack_sequence, 0, baseline_tick, bytes).Union());
    return finished(fbb);
}

void snapshot_encoder::build(std::uint32_t tick, std::span<const BodyState> bodies) {
    // FlatBuffers omits a field equal to its default; ack_sequence must be present in the
    // buffer to be patched in place, so force every field to be written.
    fbb_.ForceDefaults(true);
    build_snapshot(fbb_, tick, 0, bodies);
    built_ = true;
}

std::span<const std::uint8_t> snapshot_encoder::frame() const noexcept {
    if (!built_) return {};
    return finished(fbb_);
}

void snapshot_encoder::copy_with_ack(std::uint32_t ack_sequence, std::vector<std::uint8_t>& out) const {
    assert(built_ && "copy_with_ack() before build()");
    const auto source = frame();
    out.assign(source.begin(), source.end());
    if (out.empty()) return;
    // Our own, trusted bytes: no verification needed to navigate them.
    auto* message = GetMutableSizePrefixedMessage(out.data());
    auto* snapshot = static_cast<Snapshot*>(message->mutable_payload());
    [[maybe_unused]] const bool patched = snapshot->mutate_ack_sequence(ack_sequence);
    assert(patched && "ack_sequence missing: ForceDefaults not in effect");
}

std::vector<std::uint8_t> snapshot_encoder::frame_with_ack(std::uint32_t ack_sequence) const {
    std::vector<std::uint8_t> out;
    copy_with_ack(ack_sequence, out);
    return out;
}

}  // namespace arena::protocol
