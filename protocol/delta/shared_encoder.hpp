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
#include "protocol/delta/records.hpp"

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
    // The encoding is a function of the prepared states and the two index lists alone.
    void encode(std::span<const std::uint32_t> current, std::span<const std::uint32_t> baseline,
                std::vector<std::uint8_t>& out);

    // A body a client holds at another state than the shared state of its tick: it was left
    // out of a snapshot, and the decoder kept it as predicted (an untouched baseline body).
    struct held_body {
        std::uint32_t index = 0;  // into the state of the view it belongs to
        quantized_body state;     // what the client holds
    };

    // One client's snapshot holding only part of its view (a bandwidth budget chose which
    // bodies): `current` is the whole view, `chosen[k]` says whether current[k] goes in. A
    // body of the client's baseline view that stays in `current` but is not chosen is kept by
    // the client as predicted (written as unchanged: it is not a removal); a body new to the
    // client that is not chosen is not added yet. `baseline_held`: the baseline view's bodies
    // the client holds at other states (increasing baseline indices, each in `baseline`).
    // Writes the encoding to out, the client's resulting view (increasing state indices) to
    // `sent`, and those of its bodies it holds at other states than this one's to `held`.
    // A kept body whose prediction would leave the codec's range is removed instead.
    void encode_chosen(std::span<const std::uint32_t> current, std::span<const std::uint8_t> chosen,
                       std::span<const std::uint32_t> baseline, std::span<const held_body> baseline_held,
                       std::vector<std::uint32_t>& sent, std::vector<held_body>& held, std::vector<std::uint8_t>& out);

    [[nodiscard]] bool has_baseline() const noexcept { return base_.has_value(); }

private:
    void encode_walk(std::span<const std::uint32_t> current, std::span<const std::uint32_t> baseline,
                     std::vector<std::uint8_t>& out);
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
        std::uint32_t own_change = none;  // encode_chosen: index into own_changes_ (a held body's)
    };
    // Writes the header, the touched and the added sections from touches_ and added_indices_;
    // `checksum` is that of the client's resulting view.
    void write(std::span<const std::uint32_t> baseline, std::uint32_t checksum, std::vector<std::uint8_t>& out);

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
    struct own_change {
        records::body_change change;
        std::uint32_t owner = 0;
    };
    std::vector<own_change> own_changes_;  // encode_chosen: changes against a held state
    std::vector<std::uint8_t> kept_;       // encode_chosen: by position in current, kept as held
    // The last encoding and the views it was for: clients whose views and baselines are the
    // same (every client when each sees the whole world and they acknowledged the same tick)
    // get the same bytes, copied instead of walked again.
    bool last_valid_ = false;
    std::vector<std::uint32_t> last_current_, last_baseline_;
    std::vector<std::uint8_t> last_out_;
};

}  // namespace arena::protocol::delta
