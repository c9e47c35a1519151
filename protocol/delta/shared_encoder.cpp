#include "protocol/delta/shared_encoder.hpp"

#include <algorithm>
#include <optional>
#include <utility>

#include "protocol/delta/bits.hpp"
#include "protocol/delta/records.hpp"
#include "server/world/assert.hpp"

namespace arena::protocol::delta {
namespace {

namespace f = format;
using namespace records;

// Appends records to a pool of 64-bit words, bits least significant first, as bit_writer
// would write them; each record starts on a new word.
struct pool_sink {
    std::vector<std::uint64_t>& pool;
    const std::array<unsigned, f::class_count>& order;
    std::uint64_t bit = 0;  // bits written since the record's first word

    void append(std::uint64_t v, unsigned n) {  // n ≤ 64, higher bits of v zero
        if (n == 0) return;
        const unsigned at = bit % 64;
        if (at == 0) pool.push_back(0);
        pool.back() |= v << at;
        if (at + n > 64) pool.push_back(v >> (64 - at));
        bit += n;
    }
    void raw(std::uint64_t v, unsigned n) { append(v, n); }
    void code(f::code_class c, std::uint64_t n) {
        const unsigned k = order[c];
        const std::uint64_t m = n + (std::uint64_t{1} << k);
        const auto width = static_cast<unsigned>(std::bit_width(m));
        append(0, width - 1 - k);
        append(1, 1);
        append(m & ((std::uint64_t{1} << (width - 1)) - 1), width - 1);
    }
};

template <class Emit>
void add_record(std::vector<std::uint64_t>& pool, const std::array<unsigned, f::class_count>& order,
                std::uint32_t& word, std::uint32_t& bits, Emit emit) {
    word = static_cast<std::uint32_t>(pool.size());
    pool_sink sink{pool, order};
    emit(sink);
    bits = static_cast<std::uint32_t>(sink.bit);
}

// Copies a record into the writer, 32 bits at a time (bit_writer::put's limit).
void put_record(bit_writer& w, const std::vector<std::uint64_t>& pool, std::uint32_t word, std::uint32_t bits) {
    auto put_part = [&w, &bits](std::uint64_t v) {
        const unsigned n = bits < 32 ? bits : 32;
        w.put(v & ((std::uint64_t{1} << n) - 1), n);
        bits -= n;
    };
    while (bits > 0) {
        const std::uint64_t v = pool[word++];
        put_part(v);
        if (bits > 0) put_part(v >> 32);
    }
}

}  // namespace

void shared_encoder::prepare(view state, std::optional<view> baseline_state, elapsed_time elapsed) {
    ARENA_ASSERT(elapsed.tick_rate > 0, "a tick rate to convert ticks into seconds");
    state_ = state;
    base_ = baseline_state;
    elapsed_ = elapsed;
    last_valid_ = false;
    pool_.clear();
    stats_sink stats;
    base_to_state_.clear();
    unchanged_.clear();
    change_.clear();
    if (base_) {
        const view base = *base_;
        base_to_state_.resize(base.size(), none);
        unchanged_.resize(base.size(), 0);
        change_.resize(base.size());
        std::size_t j = 0;
        for (std::size_t i = 0; i < base.size(); ++i) {
            while (j < state.size() && state[j].id < base[i].id) ++j;
            if (j == state.size() || state[j].id != base[i].id) continue;
            base_to_state_[i] = static_cast<std::uint32_t>(j);
            const body_change d = diff(base[i], state[j], elapsed);
            unchanged_[i] = d.unchanged();
            if (!unchanged_[i]) emit_change(stats, d, state[j].owner);
        }
    }
    // Added bodies are few in a delta: a sample of the state sets their classes' orders.
    const std::size_t stride = base_ ? std::max<std::size_t>(1, state.size() / 256) : 1;
    for (std::size_t i = 0; i < state.size(); i += stride) emit_added_fields(stats, state[i]);
    for (unsigned c = 0; c < f::class_count; ++c) order_[c] = stats.best_order(static_cast<f::code_class>(c));
    added_.assign(state.size(), record{});
}

const shared_encoder::record& shared_encoder::change_record(std::uint32_t b) {
    record& r = change_[b];
    if (r.bits == none) {
        const quantized_body& now = state_[base_to_state_[b]];
        const body_change d = diff((*base_)[b], now, elapsed_);
        add_record(pool_, order_, r.word, r.bits, [&](pool_sink& s) { emit_change(s, d, now.owner); });
    }
    return r;
}

const shared_encoder::record& shared_encoder::added_record(std::uint32_t i) {
    record& r = added_[i];
    if (r.bits == none)
        add_record(pool_, order_, r.word, r.bits, [&](pool_sink& s) { emit_added_fields(s, state_[i]); });
    return r;
}

void shared_encoder::encode(std::span<const std::uint32_t> current, std::span<const std::uint32_t> baseline,
                            std::vector<std::uint8_t>& out) {
    if (!base_) baseline = {};
    // std::equal, not std::ranges::equal: the WebAssembly build's standard library lacks the latter.
    if (last_valid_ && std::equal(current.begin(), current.end(), last_current_.begin(), last_current_.end()) &&
        std::equal(baseline.begin(), baseline.end(), last_baseline_.begin(), last_baseline_.end())) {
        out.assign(last_out_.begin(), last_out_.end());
        return;
    }
    encode_walk(current, baseline, out);
    last_current_.assign(current.begin(), current.end());
    last_baseline_.assign(baseline.begin(), baseline.end());
    last_out_.assign(out.begin(), out.end());
    last_valid_ = true;
}

void shared_encoder::encode_walk(std::span<const std::uint32_t> current, std::span<const std::uint32_t> baseline,
                                 std::vector<std::uint8_t>& out) {
    // The walk: baseline bodies removed, changed or unchanged; current bodies not in the
    // baseline view are added. Both index lists follow id order, and so does base_to_state_.
    touches_.clear();
    added_indices_.clear();
    std::size_t j = 0;
    if (base_) {
        std::uint64_t gap = 0;
        for (const std::uint32_t b : baseline) {
            const std::uint32_t s = base_to_state_[b];
            if (s != none) {
                while (j < current.size() && current[j] < s) added_indices_.push_back(current[j++]);
            }
            if (s == none || j == current.size() || current[j] != s) {
                touches_.push_back({gap, b, true});  // gone from the world, or from the view
                gap = 0;
                continue;
            }
            ++j;
            if (unchanged_[b]) {
                ++gap;
            } else {
                touches_.push_back({gap, b, false});
                gap = 0;
            }
        }
    }
    while (j < current.size()) added_indices_.push_back(current[j++]);

    const view state = state_;
    write(baseline,
          checksum_of(current.size(), [&](std::size_t i) -> const quantized_body& { return state[current[i]]; }), out);
}

void shared_encoder::write(std::span<const std::uint32_t> baseline, std::uint32_t checksum,
                           std::vector<std::uint8_t>& out) {
    // This view's gap and id-gap orders (only these two classes: the others are the state's).
    width_tally gaps, id_gaps;
    for (const touch& t : touches_) gaps.add(t.gap);
    std::uint64_t next_id = 0;
    for (const std::uint32_t i : added_indices_) {
        id_gaps.add(state_[i].id - next_id);
        next_id = std::uint64_t{state_[i].id} + 1;
    }
    std::array<unsigned, f::class_count> order = order_;
    order[f::gap] = best_order(gaps);
    order[f::id_gap] = best_order(id_gaps);

    out.clear();
    bit_writer w(out);
    write_sink sink{w, order};
    w.put(f::version, f::version_bits);
    w.put(base_ ? 1 : 0, 1);
    if (base_) w.put_golomb(baseline.size(), 0);
    w.put(checksum, f::checksum_bits);
    for (unsigned c = 0; c < f::class_count; ++c) w.put_golomb(order[c], 0);
    if (base_) {
        w.put_golomb(touches_.size(), 0);
        for (const touch& t : touches_) {
            sink.code(f::gap, t.gap);
            if (t.removed) {
                emit_removed(sink);
            } else if (t.own_change != none) {
                emit_change(sink, own_changes_[t.own_change].change, own_changes_[t.own_change].owner);
            } else {
                const record& r = change_record(t.base_index);
                put_record(w, pool_, r.word, r.bits);
            }
        }
    }
    w.put_golomb(added_indices_.size(), 0);
    next_id = 0;
    for (const std::uint32_t i : added_indices_) {
        sink.code(f::id_gap, state_[i].id - next_id);
        next_id = std::uint64_t{state_[i].id} + 1;
        const record& r = added_record(i);
        put_record(w, pool_, r.word, r.bits);
    }
    w.flush();
}

namespace {

// What the decoder makes of an untouched baseline body: `from` as predicted, velocities
// unchanged (decode.cpp, body_reader::touched with mask 0); nullopt when that leaves the
// position's range, which the decoder refuses.
std::optional<quantized_body> predicted(const quantized_body& from, elapsed_time e) {
    const std::int64_t x = from.x + f::predict_displacement(from.vx, from.vx, e);
    const std::int64_t y = from.y + f::predict_displacement(from.vy, from.vy, e);
    if (!std::in_range<std::int32_t>(x) || !std::in_range<std::int32_t>(y)) return std::nullopt;
    quantized_body out = from;
    out.x = static_cast<std::int32_t>(x);
    out.y = static_cast<std::int32_t>(y);
    out.angle = f::wrap_angle(from.angle + f::predict_rotation(from.angular_velocity, from.angular_velocity, e));
    return out;
}

}  // namespace

void shared_encoder::encode_chosen(std::span<const std::uint32_t> current, std::span<const std::uint8_t> chosen,
                                   std::span<const std::uint32_t> baseline, std::span<const held_body> baseline_held,
                                   std::vector<std::uint32_t>& sent, std::vector<held_body>& held,
                                   std::vector<std::uint8_t>& out) {
    ARENA_ASSERT(chosen.size() == current.size(), "a baseline chosen for every body in view");
    touches_.clear();
    added_indices_.clear();
    own_changes_.clear();
    held.clear();
    kept_.assign(current.size(), 0);
    std::size_t j = 0;
    if (base_) {
        std::uint64_t gap = 0;
        std::size_t h = 0;
        for (const std::uint32_t b : baseline) {
            const std::uint32_t s = base_to_state_[b];
            if (s != none) {
                for (; j < current.size() && current[j] < s; ++j) {
                    if (chosen[j]) added_indices_.push_back(current[j]);
                }
            }
            while (h < baseline_held.size() && baseline_held[h].index < b) ++h;
            const quantized_body* holds =
                h < baseline_held.size() && baseline_held[h].index == b ? &baseline_held[h].state : nullptr;
            if (s == none || j == current.size() || current[j] != s) {
                touches_.push_back({gap, b, true});  // gone from the world, or from the view
                gap = 0;
                continue;
            }
            const std::size_t k = j++;
            const quantized_body& from = holds != nullptr ? *holds : (*base_)[b];
            if (!chosen[k]) {
                // Left out: the client keeps it, as predicted from what it holds.
                const std::optional<quantized_body> kept = predicted(from, elapsed_);
                if (!kept) {
                    touches_.push_back({gap, b, true});
                    gap = 0;
                    continue;
                }
                kept_[k] = 1;
                held.push_back({s, *kept});
                ++gap;
                continue;
            }
            if (holds == nullptr) {
                if (unchanged_[b]) {
                    ++gap;
                } else {
                    touches_.push_back({gap, b, false});
                    gap = 0;
                }
                continue;
            }
            // Refreshed after being left out: its change from the state the client holds.
            const records::body_change d = diff(from, state_[s], elapsed_);
            if (d.unchanged()) {
                ++gap;
                continue;
            }
            touches_.push_back({gap, b, false, static_cast<std::uint32_t>(own_changes_.size())});
            own_changes_.push_back({d, state_[s].owner});
            gap = 0;
        }
    }
    for (; j < current.size(); ++j) {
        if (chosen[j]) added_indices_.push_back(current[j]);
    }

    // The client's view after this snapshot: the chosen bodies at this state, the kept ones
    // at what it holds (held, in the same increasing order).
    sent.clear();
    for (std::size_t k = 0; k < current.size(); ++k) {
        if (chosen[k] || kept_[k]) sent.push_back(current[k]);
    }
    const view state = state_;
    std::size_t h = 0;
    const std::uint32_t checksum = checksum_of(sent.size(), [&](std::size_t i) -> const quantized_body& {
        const std::uint32_t s = sent[i];
        while (h < held.size() && held[h].index < s) ++h;
        return h < held.size() && held[h].index == s ? held[h].state : state[s];
    });
    write(baseline, checksum, out);
}

}  // namespace arena::protocol::delta
