#pragma once
// The frames a bot sends every tick, appended straight to its outgoing buffer through one
// reused FlatBufferBuilder: at 1000 bots × 60 inputs/s, encode_input()'s fresh builder and
// vector per message would be 120 000 allocations a second for nothing.
#include <cstdint>
#include <vector>

#include "protocol/messages.hpp"

namespace arena::bots {

void append_input(flatbuffers::FlatBufferBuilder& fbb, const protocol::input_msg& input,
                  std::vector<std::uint8_t>& out);
void append_ping(flatbuffers::FlatBufferBuilder& fbb, std::uint64_t client_time, std::vector<std::uint8_t>& out);

}  // namespace arena::bots
