#pragma once
// Test helper: runs a byte stream through a frame_reader the way a socket would deliver it.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "protocol/framing.hpp"

namespace arena::protocol::test {

struct stream_outcome {
    std::vector<std::vector<std::uint8_t>> frames;  // every complete frame, prefix included
    std::string error;                              // the reader's error, if it failed
    std::size_t consumed = 0;                       // bytes the reader took
    std::size_t buffered = 0;                       // bytes held at the end (partial frame)
};

// Feeds stream in pieces of at most chunk bytes, collecting frames as they complete.
stream_outcome read_stream(std::span<const std::uint8_t> stream, std::size_t chunk,
                           std::uint32_t max_body = max_client_frame_body);

// Concatenates frames into one stream.
std::vector<std::uint8_t> concat(const std::vector<std::vector<std::uint8_t>>& frames);

}  // namespace arena::protocol::test
