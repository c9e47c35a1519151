#pragma once
// The server's encoder for many clients. Every client's view is a subset of the same world
// state, encoded against a subset of the same few baseline states (the ticks clients
// acknowledged), so the per-body work, the difference from the baseline and the bits of each
// body's record, is done once per pair of states and shared. Encoding one client's view is
// then a walk over its indices that copies precomputed bits: the cost per client grows with
// its view, with a small constant, not with the world.
//
// The output is the format of codec.hpp, read by the same decode(). The only difference from
// encode() is which Exp-Golomb orders are chosen: the body fields' orders come from the whole
// state instead of each view (the decoder reads them from the header either way).
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "protocol/delta/codec.hpp"
#include "protocol/delta/format.hpp"

namespace arena::protocol::delta {

class shared_encoder {
public:
    // state: every body now, sorted by strictly increasing id; baseline_state: every body at
    // the baseline tick, likewise, or nullopt to encode views in full. Both spans must stay
    // valid while encode() is used.
    void prepare(view state, std::optional<view> baseline_state, elapsed_time elapsed);

    // One client's view: `current` holds increasing indices into the state; `baseline` (ignored
    // without a baseline state) increasing indices into the baseline state, exactly the view
    // the client holds. Writes the encoding to out (cleared first; its capacity is reused).
    void encode(std::span<const std::uint32_t> current, std::span<const std::uint32_t> baseline,
                std::vector<std::uint8_t>& out);

    [[nodiscard]] bool has_baseline() const noexcept { return base_.has_value(); }

private:
    // A run of bits in pool_, starting at a word boundary; built on first use, since a tick's
    // clients together touch only the bodies near them (bits == none: not built yet).
    struct record {
        std::uint32_t word = 0;
        std::uint32_t bits = none;
    };
    static constexpr std::uint32_t none = ~0u;
    const record& change_record(std::uint32_t base_index);
    const record& added_record(std::uint32_t state_index);
    // One baseline body in a client's walk: removed, or changed (its record), after `gap`
    // unchanged ones.
    struct touch {
        std::uint64_t gap = 0;
        std::uint32_t base_index = 0;
        bool removed = false;
    };

    view state_;
    std::optional<view> base_;
    elapsed_time elapsed_;
    std::array<unsigned, format::class_count> order_{};
    std::vector<std::uint32_t> base_to_state_;  // baseline index → state index, or none
    std::vector<std::uint8_t> unchanged_;       // by baseline index: exactly as predicted
    std::vector<record> change_;                // by baseline index: its record when changed
    std::vector<record> added_;                 // by state index: its record after the id gap
    std::vector<std::uint64_t> pool_;
    // One client's walk, reused.
    std::vector<touch> touches_;
    std::vector<std::uint32_t> added_indices_;
};

}  // namespace arena::protocol::delta
