#pragma once
// FNV-1a, the one hash function of the code base: 64-bit for the world's state and config
// hashes and Welcome.world_config_hash, 32-bit for the replay records' checksums. Defined in a
// few lines (h ^= byte; h *= prime, from an offset basis), so any client language can
// reimplement it, and every step is a bijection of the state, so any single changed byte
// changes the result. Multi-byte values go in little-endian, field by field, never as struct
// bytes (padding would leak in). Header-only and standard library only, so the protocol and
// the replay code use it without linking the world.
#include <bit>
#include <cstdint>
#include <span>
#include <string_view>

namespace arena::world {

template <class Word, Word offset_basis, Word prime>
class basic_fnv1a {
public:
    constexpr void add_u8(std::uint8_t v) noexcept {
        h_ ^= v;
        h_ *= prime;  // unsigned: wraps by definition
    }
    constexpr void add_u32(std::uint32_t v) noexcept {
        for (int i = 0; i < 4; ++i) add_u8(static_cast<std::uint8_t>(v >> (8 * i)));
    }
    constexpr void add_u64(std::uint64_t v) noexcept {
        for (int i = 0; i < 8; ++i) add_u8(static_cast<std::uint8_t>(v >> (8 * i)));
    }
    // By its bits: −0.0 and 0.0 differ.
    constexpr void add_f32(float v) noexcept { add_u32(std::bit_cast<std::uint32_t>(v)); }
    constexpr void add_bytes(std::span<const std::uint8_t> bytes) noexcept {
        for (std::uint8_t b : bytes) add_u8(b);
    }
    constexpr void add_bytes(std::string_view text) noexcept {
        for (char c : text) add_u8(static_cast<std::uint8_t>(c));
    }
    [[nodiscard]] constexpr Word value() const noexcept { return h_; }

private:
    Word h_ = offset_basis;
};

using fnv1a_64 = basic_fnv1a<std::uint64_t, 0xcbf29ce484222325ULL, 0x100000001b3ULL>;
using fnv1a_32 = basic_fnv1a<std::uint32_t, 0x811c9dc5U, 0x01000193U>;

}  // namespace arena::world
