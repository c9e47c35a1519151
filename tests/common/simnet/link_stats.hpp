#pragma once
// What a simulated link did, for the tests' own checks and their failure messages.
#include <cstdint>

namespace arena::simnet {

struct link_stats {
    std::uint64_t sent = 0;             // messages (datagram) or segments (stream) handed to the link
    std::uint64_t sent_bytes = 0;       // bytes handed to the link
    std::uint64_t lost = 0;             // transmissions lost (a resent one counts each time)
    std::uint64_t retransmissions = 0;  // resends of streams' segments and reliable messages
    std::uint64_t duplicated = 0;       // extra copies made (a stream's receiver discards them)
    std::uint64_t held_back = 0;        // messages delayed further so that later ones overtake them
    std::uint64_t delivered = 0;        // messages (datagram) or segments (stream) handed to the receiver
};

}  // namespace arena::simnet
