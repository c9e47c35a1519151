#include "protocol/config_hash.hpp"

namespace arena::protocol {

std::uint64_t world_config_hash(std::string_view world_config) noexcept {
    std::uint64_t h = 14695981039346656037ull;  // FNV-1a 64 offset basis
    for (const char c : world_config) {
        h ^= static_cast<std::uint8_t>(c);
        h *= 1099511628211ull;  // FNV-1a 64 prime; unsigned overflow wraps by definition
    }
    return h;
}

}  // namespace arena::protocol
