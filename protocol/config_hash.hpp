#pragma once
// Welcome.world_config_hash: lets a predicting client check that it builds the world from
// exactly the configuration the server runs. FNV-1a 64 over the bytes (server/world/fnv1a.hpp),
// because it is defined in a few lines and so is easy to reimplement in any client language.
#include <cstdint>
#include <string_view>

namespace arena::protocol {

// FNV-1a, 64-bit: h = 14695981039346656037; for each byte b: h ^= b; h *= 1099511628211.
[[nodiscard]] std::uint64_t world_config_hash(std::string_view world_config) noexcept;

}  // namespace arena::protocol
