#pragma once
// A few lanes of `real` computed at once: the sub-stepped solver's contact rows (soft_lanes.hpp)
// solve `wide_lanes` contacts per instruction.
//
// GCC's and Clang's vector extension (`vector_size`), not intrinsics: + − × ÷ and the
// comparisons apply the scalar IEEE operation to each lane, so a lane's result is the bits the
// same scalar expression gives, on x86-64 (SSE2), aarch64 (NEON) and WebAssembly (split into
// scalars when SIMD is off). No FMA: -ffp-contract=off covers vector arithmetic as it does
// scalar. The few things that are not one operation per lane are spelt out here (max, min,
// clamp as selects written the way std::max, std::min and std::clamp define them), so that no
// target's instruction with a different rule for signed zeros or NaN can slip in.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "server/world/types.hpp"

namespace arena::world {

// Four lanes: one SSE or NEON register. The results do not depend on the width (a lane is
// one contact, and no operation mixes lanes), only the speed does.
inline constexpr size_t wide_lanes = 4;

using wide = real __attribute__((vector_size(sizeof(real) * wide_lanes)));
using wide_mask = int32_t __attribute__((vector_size(sizeof(int32_t) * wide_lanes)));  // −1 true, 0 false

static_assert(sizeof(real) == sizeof(int32_t), "the masks are as wide as the lanes");

namespace detail {
template <class Lane, size_t... I>
wide wide_of(Lane&& lane, std::index_sequence<I...>) {
    return wide{lane(I)...};
}
template <class Lane, size_t... I>
wide_mask mask_of(Lane&& lane, std::index_sequence<I...>) {
    return wide_mask{(lane(I) ? -1 : 0)...};
}
}  // namespace detail

// Every lane the same value.
inline wide splat(real value) {
    return detail::wide_of([value](size_t) { return value; }, std::make_index_sequence<wide_lanes>{});
}

// Lane i is lane(i).
template <class Lane>
wide wide_of(Lane&& lane) {
    return detail::wide_of(lane, std::make_index_sequence<wide_lanes>{});
}

// Lane i set when lane(i) is true.
template <class Lane>
wide_mask mask_of(Lane&& lane) {
    return detail::mask_of(lane, std::make_index_sequence<wide_lanes>{});
}

// Lane by lane, `if_true` where the mask is set, else `if_false`: bits chosen, none computed.
inline wide select(wide_mask mask, wide if_true, wide if_false) {
    return std::bit_cast<wide>((mask & std::bit_cast<wide_mask>(if_true)) |
                               (~mask & std::bit_cast<wide_mask>(if_false)));
}

// As std::max, std::min and std::clamp, lane by lane: (a < b) ? b : a and so on.
inline wide max(wide a, wide b) {
    return select(a < b, b, a);
}
inline wide min(wide a, wide b) {
    return select(b < a, b, a);
}
inline wide clamp(wide v, wide lo, wide hi) {
    return select(v < lo, lo, select(hi < v, hi, v));
}

}  // namespace arena::world
