#pragma once
// Ids that cross module boundaries (world ↔ match ↔ replay ↔ protocol encode), each its own
// type, so that a player id cannot be handed where a body id is wanted. Made only explicitly
// from a number and read back with value(); 0 means none, as on the wire. The same 32 bits as
// before: the wire format, the world hash and replay files are unchanged.
#include <compare>
#include <cstddef>
#include <cstdint>
#include <functional>

namespace arena::world {

template <class Tag>
class strong_id {
public:
    constexpr strong_id() = default;
    constexpr explicit strong_id(uint32_t value) : value_(value) {}
    constexpr uint32_t value() const { return value_; }
    // True unless it is the "none" id, 0.
    constexpr explicit operator bool() const { return value_ != 0; }
    friend constexpr auto operator<=>(strong_id, strong_id) = default;

private:
    uint32_t value_ = 0;
};

struct body_id_tag;
struct player_id_tag;
using body_id = strong_id<body_id_tag>;      // world::body::id
using player_id = strong_id<player_id_tag>;  // a match's player, world::body::owner

}  // namespace arena::world

template <class Tag>
struct std::hash<arena::world::strong_id<Tag>> {
    std::size_t operator()(arena::world::strong_id<Tag> id) const noexcept { return std::hash<uint32_t>{}(id.value()); }
};
