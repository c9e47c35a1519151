#pragma once
// Little-endian integers in byte buffers, whatever the host's byte order: the length prefixes
// of wire frames and replay records, the replay checksums, and the fields the hashes
// serialise. Header-only and standard library only, so the protocol and the replay code use
// it without linking the world.
#include <cstdint>
#include <vector>

namespace arena::world {

[[nodiscard]] constexpr std::uint32_t load_le32(const std::uint8_t* p) noexcept {
    return std::uint32_t{p[0]} | (std::uint32_t{p[1]} << 8) | (std::uint32_t{p[2]} << 16) | (std::uint32_t{p[3]} << 24);
}

constexpr void store_le32(std::uint8_t* p, std::uint32_t v) noexcept {
    for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}

inline void append_le32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

}  // namespace arena::world
