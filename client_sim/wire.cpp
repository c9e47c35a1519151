#include "client_sim/wire.hpp"

namespace arena::bots {

namespace {

void append_finished(const flatbuffers::FlatBufferBuilder& fbb, std::vector<std::uint8_t>& out) {
    out.insert(out.end(), fbb.GetBufferPointer(), fbb.GetBufferPointer() + fbb.GetSize());
}

}  // namespace

void append_input(flatbuffers::FlatBufferBuilder& fbb, const protocol::input_msg& in, std::vector<std::uint8_t>& out) {
    fbb.Clear();  // keeps its block
    protocol::finish_message(fbb, protocol::Payload::Input, protocol::create_input(fbb, in).Union());
    append_finished(fbb, out);
}

void append_ping(flatbuffers::FlatBufferBuilder& fbb, std::uint64_t client_time, std::vector<std::uint8_t>& out) {
    fbb.Clear();
    protocol::finish_message(fbb, protocol::Payload::Ping, protocol::CreatePing(fbb, client_time).Union());
    append_finished(fbb, out);
}

}  // namespace arena::bots
