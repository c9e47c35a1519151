#include "server/replay/record_format.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "protocol/player_name.hpp"
#include "protocol/replay_generated.h"
#include "server/replay/status.hpp"
#include "server/world/assert.hpp"
#include "server/world/fnv1a.hpp"
#include "server/world/little_endian.hpp"

namespace arena::replay {
namespace fb = protocol::replay;

namespace {

bool is_known_content(fb::Content type) {
    // The generated verifier accepts NONE and unknown tags (forward compatibility); a replay
    // cannot skip a record it does not understand, so we refuse both.
    const auto v = static_cast<uint8_t>(type);
    return v >= static_cast<uint8_t>(fb::Content::Header) && v <= static_cast<uint8_t>(fb::Content::MAX);
}

std::string string_or_empty(const flatbuffers::String* s) {
    return s ? s->str() : std::string();
}

header decode_header(const fb::Header& h) {
    header out;
    out.format_version = h.format_version();
    out.protocol_version = h.protocol_version();
    out.world_version = h.world_version();
    out.world_config = string_or_empty(h.world_config());
    out.preset = string_or_empty(h.preset());
    out.seed = h.seed();
    out.tick_rate = h.tick_rate();
    out.hash_interval = h.hash_interval();
    out.start_tick = h.start_tick();
    out.start_hash = h.start_hash();
    return out;
}

protocol::result<record> decode_tick(const fb::Tick& t) {
    match::tick_record out;
    out.tick = t.tick();
    if (const auto* joins = t.joins())
        for (const uint32_t id : *joins) out.joins.emplace_back(id);
    if (const auto* names = t.join_names()) {
        // One name per join, each one a Hello could carry: a file's bytes reach the scoreboard.
        if (names->size() != out.joins.size())
            return protocol::result<record>::failure("Tick " + std::to_string(out.tick) + ": " +
                                                     std::to_string(names->size()) + " join names for " +
                                                     std::to_string(out.joins.size()) + " joins");
        out.join_names.reserve(names->size());
        for (const flatbuffers::String* name : *names) {
            std::string text = string_or_empty(name);
            if (auto problem = protocol::player_name_problem(text, protocol::max_player_name_bytes))
                return protocol::result<record>::failure("Tick " + std::to_string(out.tick) + ": join name " +
                                                         std::to_string(out.join_names.size()) + ": " + *problem);
            out.join_names.push_back(std::move(text));
        }
    }
    if (const auto* leaves = t.leaves())
        for (const uint32_t id : *leaves) out.leaves.emplace_back(id);
    if (const auto* inputs = t.inputs()) {
        const auto* rewinds = t.rewinds();
        if (rewinds != nullptr && rewinds->size() != inputs->size())
            return protocol::result<record>::failure("Tick " + std::to_string(out.tick) + ": " +
                                                     std::to_string(rewinds->size()) + " rewinds for " +
                                                     std::to_string(inputs->size()) + " inputs");
        out.inputs.reserve(inputs->size());
        for (const fb::TickInput* in : *inputs) {
            world::body_input b{world::body_id{in->body_id()}, {in->thrust(), in->turn(), in->buttons()}};
            if (rewinds != nullptr) {
                b.input.rewind = rewinds->Get(static_cast<flatbuffers::uoffset_t>(out.inputs.size()));
                if (b.input.rewind > world::max_rewind)
                    return protocol::result<record>::failure("Tick " + std::to_string(out.tick) + ": input for body " +
                                                             std::to_string(in->body_id()) + ": rewind " +
                                                             std::to_string(b.input.rewind) + " over the most, " +
                                                             std::to_string(world::max_rewind));
            }
            // NaN must never enter the world, whatever the file says.
            if (auto problem = world::check_input(b.input)) {
                return protocol::result<record>::failure("Tick " + std::to_string(out.tick) + ": input for body " +
                                                         std::to_string(b.body_id.value()) + ": " + *problem);
            }
            out.inputs.push_back(b);
        }
    }
    return success_as<record>(std::move(out));
}

}  // namespace

uint32_t record_checksum(std::span<const uint8_t> body) {
    world::fnv1a_32 h;
    h.add_bytes(body);
    return h.value();
}

void record_encoder::finish_into(std::vector<uint8_t>& out) {
    const uint8_t* data = builder_.GetBufferPointer();
    const size_t size = builder_.GetSize();  // prefix included
    out.insert(out.end(), data, data + size);
    world::append_le32(out, record_checksum({data + record_prefix_size, size - record_prefix_size}));
    builder_.Clear();
}

void record_encoder::append(const header& h, std::vector<uint8_t>& out) {
    const auto config = builder_.CreateString(h.world_config);
    const auto preset = builder_.CreateString(h.preset);
    fb::HeaderBuilder b(builder_);
    b.add_format_version(h.format_version);
    b.add_protocol_version(h.protocol_version);
    b.add_world_version(h.world_version);
    b.add_world_config(config);
    b.add_preset(preset);
    b.add_seed(h.seed);
    b.add_tick_rate(h.tick_rate);
    b.add_hash_interval(h.hash_interval);
    b.add_start_tick(h.start_tick);
    b.add_start_hash(h.start_hash);
    const auto content = b.Finish();
    fb::FinishSizePrefixedRecordBuffer(builder_, fb::CreateRecord(builder_, fb::Content::Header, content.Union()));
    finish_into(out);
}

void record_encoder::append(const match::tick_record& t, std::vector<uint8_t>& out) {
    // Empty vectors are left out: most ticks have no joins or leaves.
    flatbuffers::Offset<flatbuffers::Vector<uint32_t>> joins, leaves;
    flatbuffers::Offset<flatbuffers::Vector<const fb::TickInput*>> inputs;
    flatbuffers::Offset<flatbuffers::Vector<uint16_t>> rewinds;
    // The ids' numbers, as they always were on disk.
    auto numbers = [](const auto& ids) {
        std::vector<uint32_t> out;
        out.reserve(ids.size());
        for (const auto id : ids) out.push_back(id.value());
        return out;
    };
    if (!t.joins.empty()) joins = builder_.CreateVector(numbers(t.joins));
    flatbuffers::Offset<flatbuffers::Vector<flatbuffers::Offset<flatbuffers::String>>> names;
    if (!t.joins.empty() && t.join_names.size() == t.joins.size()) names = builder_.CreateVectorOfStrings(t.join_names);
    if (!t.leaves.empty()) leaves = builder_.CreateVector(numbers(t.leaves));
    if (!t.inputs.empty()) {
        fb::TickInput* slots = nullptr;
        inputs = builder_.CreateUninitializedVectorOfStructs(t.inputs.size(), &slots);
        for (size_t i = 0; i < t.inputs.size(); ++i) {
            const world::body_input& in = t.inputs[i];
            slots[i] = fb::TickInput(in.body_id.value(), in.input.thrust, in.input.turn, in.input.buttons);
        }
        // Rewinds only when one is not 0: a match without lag compensation records as before.
        if (std::any_of(t.inputs.begin(), t.inputs.end(),
                        [](const world::body_input& in) { return in.input.rewind; })) {
            std::vector<uint16_t> values;
            values.reserve(t.inputs.size());
            for (const world::body_input& in : t.inputs) values.push_back(in.input.rewind);
            rewinds = builder_.CreateVector(values);
        }
    }
    fb::TickBuilder b(builder_);
    b.add_tick(t.tick);
    if (!joins.IsNull()) b.add_joins(joins);
    if (!leaves.IsNull()) b.add_leaves(leaves);
    if (!inputs.IsNull()) b.add_inputs(inputs);
    if (!names.IsNull()) b.add_join_names(names);
    if (!rewinds.IsNull()) b.add_rewinds(rewinds);
    const auto content = b.Finish();
    fb::FinishSizePrefixedRecordBuffer(builder_, fb::CreateRecord(builder_, fb::Content::Tick, content.Union()));
    finish_into(out);
}

void record_encoder::append(const hash_check& c, std::vector<uint8_t>& out) {
    const auto content = fb::CreateHash(builder_, c.tick, c.hash);
    fb::FinishSizePrefixedRecordBuffer(builder_, fb::CreateRecord(builder_, fb::Content::Hash, content.Union()));
    finish_into(out);
}

void record_encoder::append(const end_marker& e, std::vector<uint8_t>& out) {
    const auto content = fb::CreateEnd(builder_, e.tick, e.hash);
    fb::FinishSizePrefixedRecordBuffer(builder_, fb::CreateRecord(builder_, fb::Content::End, content.Union()));
    finish_into(out);
}

protocol::result<record> decode_record(std::span<const uint8_t> frame) {
    ARENA_ASSERT(reinterpret_cast<std::uintptr_t>(frame.data()) % 8 == 0, "a record frame 8-byte aligned");
    using r = protocol::result<record>;
    if (frame.size() < record_prefix_size + min_record_body || frame.size() > record_prefix_size + max_record_body) {
        return r::failure("record of " + std::to_string(frame.size()) + " bytes is outside the valid sizes");
    }
    if (reinterpret_cast<std::uintptr_t>(frame.data()) % 8 != 0) {
        // Our bug, not the file's, but reading in place would be undefined behaviour.
        return r::failure("record buffer is not 8-byte aligned");
    }
    if (std::memcmp(frame.data() + record_prefix_size + 4, record_identifier, 4) != 0) {
        return r::failure("file identifier is not \"ARPL\": not an Arena replay record");
    }
    flatbuffers::Verifier::Options options;
    // Record -> content table; vectors and strings do not count. Tight limits keep the
    // Verifier's work proportional to the record's size.
    options.max_depth = 4;
    options.max_tables = 4;
    options.check_alignment = true;
    flatbuffers::Verifier verifier(frame.data(), frame.size(), options);
    if (!verifier.VerifySizePrefixedBuffer<fb::Record>(record_identifier)) {
        return r::failure(
            "FlatBuffer verification failed: an offset, size, alignment or nesting limit is out of range");
    }
    const fb::Record* rec = fb::GetSizePrefixedRecord(frame.data());
    if (!is_known_content(rec->content_type())) {
        return r::failure("unknown record type " + std::to_string(static_cast<unsigned>(rec->content_type())) +
                          (rec->content_type() == fb::Content::NONE ? " (NONE)" : ""));
    }
    if (rec->content() == nullptr) {
        return r::failure(std::string("record type ") + fb::EnumNameContent(rec->content_type()) + " has no table");
    }
    switch (rec->content_type()) {
        case fb::Content::Header:
            return success_as<record>(decode_header(*rec->content_as_Header()));
        case fb::Content::Tick:
            return decode_tick(*rec->content_as_Tick());
        case fb::Content::Hash: {
            const fb::Hash& h = *rec->content_as_Hash();
            return success_as<record>(hash_check{h.tick(), h.hash()});
        }
        case fb::Content::End: {
            const fb::End& e = *rec->content_as_End();
            return success_as<record>(end_marker{e.tick(), e.hash()});
        }
        default:
            return r::failure("unknown record type");  // unreachable: is_known_content
    }
}

const char* record_type_name(const record& r) {
    static constexpr const char* names[] = {"Header", "Tick", "Hash", "End"};
    return names[r.index()];
}

}  // namespace arena::replay
