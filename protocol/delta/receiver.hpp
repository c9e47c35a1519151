#pragma once
// The client's end of delta snapshots (README.md, "Use: server and client"): keeps the views
// it decoded, decodes each delta Snapshot against the baseline it names, and says which tick
// to acknowledge in the next Input. Used by arena-bots and the tests; a game client in C++
// can use it as it is.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "protocol/decode.hpp"
#include "protocol/delta/codec.hpp"

namespace arena::protocol::delta {

class receiver {
public:
    // tick_rate: Welcome.tick_rate (> 0). keep: decoded views kept as possible baselines; the
    // server encodes against the newest one acknowledged, so a round trip's worth is enough.
    explicit receiver(std::uint16_t tick_rate, std::size_t keep = 32);

    // A Snapshot carrying `delta`: the view it holds, sorted by id, valid until the next call.
    // On a failure (a baseline not kept, a checksum mismatch, malformed bytes) every kept view
    // is dropped, so that the next acknowledgement is 0 and the server sends a full view.
    [[nodiscard]] result<std::span<const quantized_body>> receive(const snapshot_view& snapshot);

    // The tick to acknowledge: the newest view decoded and kept, 0 when none.
    [[nodiscard]] std::uint32_t ack() const noexcept { return newest_; }

private:
    struct kept_view {
        std::uint32_t tick = 0;
        std::vector<quantized_body> bodies;
    };
    const kept_view* find(std::uint32_t tick) const;

    std::uint16_t tick_rate_;
    std::vector<kept_view> kept_;  // a ring: kept_[next_] is replaced next
    std::size_t next_ = 0;
    std::uint32_t newest_ = 0;
};

}  // namespace arena::protocol::delta
