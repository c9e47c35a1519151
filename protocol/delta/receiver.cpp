#include "protocol/delta/receiver.hpp"

#include <algorithm>
#include <string>

namespace arena::protocol::delta {

receiver::receiver(std::uint16_t tick_rate, std::size_t keep)
    : tick_rate_(tick_rate), kept_(std::max<std::size_t>(keep, 1)) {}

const receiver::kept_view* receiver::find(std::uint32_t tick) const {
    for (const kept_view& k : kept_) {
        if (k.tick == tick) return &k;
    }
    return nullptr;
}

result<std::span<const quantized_body>> receiver::receive(const snapshot_view& snapshot) {
    using out = result<std::span<const quantized_body>>;
    auto fail = [this, &snapshot](const std::string& reason) {
        for (kept_view& k : kept_) k.tick = 0;
        newest_ = 0;
        return out::failure("snapshot " + std::to_string(snapshot.tick) + ": " + reason);
    };
    if (!snapshot.is_delta) return fail("not a delta snapshot");
    if (snapshot.tick == 0) return fail("tick 0");
    std::optional<view> baseline;
    if (snapshot.baseline_tick != 0) {
        if (snapshot.baseline_tick >= snapshot.tick) return fail("baseline tick not before the snapshot");
        const kept_view* b = find(snapshot.baseline_tick);
        if (b == nullptr) return fail("baseline " + std::to_string(snapshot.baseline_tick) + " not kept");
        baseline = view(b->bodies);
    }
    const elapsed_time elapsed{snapshot.baseline_tick == 0 ? 0 : snapshot.tick - snapshot.baseline_tick, tick_rate_};
    auto decoded = decode(snapshot.delta, baseline, elapsed);
    if (!decoded) return fail(decoded.error);
    // The slot replaced may hold the baseline just used: the decoded view is already a copy.
    kept_view& slot = kept_[next_];
    next_ = (next_ + 1) % kept_.size();
    slot.tick = snapshot.tick;
    slot.bodies = std::move(decoded.value);
    newest_ = std::max(newest_, snapshot.tick);
    return out::success(std::span<const quantized_body>(slot.bodies));
}

}  // namespace arena::protocol::delta
