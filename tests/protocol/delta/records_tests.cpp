// The encoders' order search (protocol/delta/records.hpp): a tally that counts only the widths
// present picks the same Exp-Golomb order as a search over every width, so the bytes on the
// wire do not depend on how the tally is kept.
#include <catch2/catch.hpp>

#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "protocol/delta/records.hpp"
#include "scenes.hpp"

namespace ad = arena::protocol::delta;

namespace {

// The search as it reads in the format's description: every order up to the cap, every one
// of the 65 widths, each value estimated by the smallest value of its width.
unsigned order_over_all_widths(const std::vector<std::uint64_t>& values) {
    std::array<std::uint64_t, 65> counts{};
    for (const std::uint64_t v : values) ++counts[std::bit_width(v)];
    unsigned widest = 0;
    for (unsigned w = 0; w < 65; ++w)
        if (counts[w] != 0) widest = w;
    unsigned best = 0;
    std::uint64_t best_bits = UINT64_MAX;
    for (unsigned k = 0; k <= widest && k <= ad::max_golomb_order; ++k) {
        std::uint64_t bits = 0;
        for (unsigned w = 0; w < 65; ++w) {
            const std::uint64_t n = w == 0 ? 0 : std::uint64_t{1} << (w - 1);
            bits += counts[w] * ad::golomb_bits(n, k);
        }
        if (bits < best_bits) {
            best_bits = bits;
            best = k;
        }
    }
    return best;
}

}  // namespace

TEST_CASE("The order search over the widths present picks the order a search over all widths picks",
          "[protocol][delta]") {
    ad::test::rng r(32);
    for (int round = 0; round < 2000; ++round) {
        // A few values of a few magnitudes, as a class of one snapshot holds, sometimes none,
        // sometimes the extremes (width 0 and width 64).
        std::vector<std::uint64_t> values;
        const auto count = r.below(40);
        const auto spread = 1 + r.below(64);
        for (std::uint64_t i = 0; i < count; ++i) {
            const auto width = r.below(spread + 1);
            // The top bit of the width, and random bits below it.
            const std::uint64_t below_top = width <= 1 ? 0 : r.next() >> (65 - width);
            std::uint64_t v = width == 0 ? 0 : (std::uint64_t{1} << (width - 1)) | below_top;
            if (r.chance(0.02)) v = r.chance(0.5) ? 0 : UINT64_MAX;
            values.push_back(v);
        }
        ad::records::width_tally tally;
        for (const std::uint64_t v : values) tally.add(v);
        INFO("round " << round << ", " << values.size() << " values");
        REQUIRE(ad::records::best_order(tally) == order_over_all_widths(values));
        for (unsigned w = 0; w < 65; ++w) {
            std::uint64_t expected = 0;
            for (const std::uint64_t v : values) expected += std::bit_width(v) == w ? 1 : 0;
            REQUIRE(tally.count(w) == expected);
        }
    }
}
