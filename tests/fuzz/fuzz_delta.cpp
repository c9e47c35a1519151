// Fuzz target: the client's end of delta snapshots, fed bytes a hostile or broken server could
// send. Byte 0 chooses the case (bit 0: decode against the baseline below; bits 1-3: ticks
// since it); the rest is the codec's bytes. Whatever decode() accepts must be a view it would
// itself produce: sorted by id, within the limit, and re-encoded and decoded to the same view.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <vector>

#include "protocol/delta/codec.hpp"

namespace {

namespace ad = arena::protocol::delta;

// A fixed baseline: 40 bodies, ids with gaps, some owned, moving.
std::vector<ad::quantized_body> make_baseline() {
    std::vector<ad::quantized_body> out;
    for (std::uint32_t i = 0; i < 40; ++i) {
        const auto k = static_cast<std::int32_t>(i);
        out.push_back({3 * i + 1, i % 4 == 0 ? i / 4 + 1 : 0, 2560 * k, -1280 * k, 32 * (k - 20), 16 * k,
                       static_cast<std::int16_t>(1000 * k), static_cast<std::int16_t>(64 * (k % 7))});
    }
    return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::vector<ad::quantized_body> baseline = make_baseline();
    if (size == 0) return 0;
    const bool against_baseline = (data[0] & 1) != 0;
    const ad::elapsed_time elapsed{static_cast<std::uint32_t>((data[0] >> 1) & 7), 60};
    const std::span<const std::uint8_t> bytes(data + 1, size - 1);
    const std::optional<ad::view> base = against_baseline ? std::optional<ad::view>(baseline) : std::nullopt;
    const ad::decode_limits limits{4096};
    const auto decoded = ad::decode(bytes, base, elapsed, limits);
    if (!decoded) return 0;
    const std::vector<ad::quantized_body>& view = decoded.value;
    if (view.size() > limits.max_bodies) std::abort();
    for (std::size_t i = 1; i < view.size(); ++i) {
        if (!(view[i - 1].id < view[i].id)) std::abort();
    }
    const auto again = ad::decode(ad::encode(view, base, elapsed), base, elapsed, limits);
    if (!again || again.value != view) std::abort();
    return 0;
}
