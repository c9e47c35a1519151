#include "stream.hpp"

#include <algorithm>

namespace arena::protocol::test {

stream_outcome read_stream(std::span<const std::uint8_t> stream, std::size_t chunk, std::uint32_t max_body) {
    frame_reader reader(max_body);
    stream_outcome out;
    std::size_t offset = 0;
    while (offset < stream.size() && !reader.failed()) {
        auto piece = stream.subspan(offset, std::min(chunk, stream.size() - offset));
        // One socket read may hold several frames: drain it before the next read.
        while (!piece.empty() && !reader.failed()) {
            const std::size_t n = reader.feed(piece);
            piece = piece.subspan(n);
            offset += n;
            out.consumed += n;
            if (reader.has_frame()) {
                out.frames.emplace_back(reader.frame().begin(), reader.frame().end());
                reader.next();
            }
        }
    }
    out.error = std::string(reader.error());
    out.buffered = reader.buffered();
    return out;
}

std::vector<std::uint8_t> concat(const std::vector<std::vector<std::uint8_t>>& frames) {
    std::vector<std::uint8_t> all;
    for (const auto& f : frames) all.insert(all.end(), f.begin(), f.end());
    return all;
}

}  // namespace arena::protocol::test
