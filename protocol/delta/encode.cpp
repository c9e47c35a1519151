// The encoder: two passes over the same emit functions. The first only counts how long each
// class's values are, to pick each class's Exp-Golomb order; the second writes the bits.
#include <array>
#include <bit>
#include <cstdint>

#include "protocol/delta/bits.hpp"
#include "protocol/delta/codec.hpp"
#include "protocol/delta/format.hpp"
#include "protocol/delta/records.hpp"
#include "server/world/assert.hpp"

namespace arena::protocol::delta {
namespace {

namespace f = format;
using namespace records;

[[maybe_unused]] bool strictly_sorted(view v) noexcept {
    for (std::size_t i = 1; i < v.size(); ++i) {
        if (!(v[i - 1].id < v[i].id)) return false;
    }
    return true;
}

// Baseline bodies that are removed or differ from their prediction, each after the count of
// unchanged ones before it. Returns how many it emitted.
template <class Sink>
std::uint64_t emit_touched(Sink& s, view cur, view base, elapsed_time e) {
    std::uint64_t touched = 0;
    std::uint64_t gap = 0;
    std::size_t j = 0;
    for (const quantized_body& b : base) {
        while (j < cur.size() && cur[j].id < b.id) ++j;  // added bodies: emit_added's business
        if (j == cur.size() || cur[j].id != b.id) {
            s.code(f::gap, gap);
            emit_removed(s);
            gap = 0;
            ++touched;
            continue;
        }
        const body_change d = diff(b, cur[j], e);
        if (d.unchanged()) {
            ++gap;
        } else {
            s.code(f::gap, gap);
            emit_change(s, d, cur[j].owner);
            gap = 0;
            ++touched;
        }
        ++j;
    }
    return touched;
}

// Current bodies not in the baseline, in full. Returns how many it emitted.
template <class Sink>
std::uint64_t emit_added(Sink& s, view cur, view base) {
    std::uint64_t added = 0;
    std::uint64_t next_id = 0;  // the smallest id the next added body can have
    std::size_t i = 0;
    for (const quantized_body& c : cur) {
        while (i < base.size() && base[i].id < c.id) ++i;
        if (i < base.size() && base[i].id == c.id) continue;
        s.code(f::id_gap, c.id - next_id);
        emit_added_fields(s, c);
        next_id = std::uint64_t{c.id} + 1;
        ++added;
    }
    return added;
}

}  // namespace

void encode(view current, std::optional<view> baseline, elapsed_time elapsed, std::vector<std::uint8_t>& out) {
    ARENA_ASSERT(strictly_sorted(current), "views are sorted by strictly increasing id");
    ARENA_ASSERT(!baseline || strictly_sorted(*baseline), "views are sorted by strictly increasing id");
    ARENA_ASSERT(elapsed.tick_rate > 0, "a tick rate to convert ticks into seconds");
    const view base = baseline ? *baseline : view{};

    stats_sink stats;
    const std::uint64_t touched = baseline ? emit_touched(stats, current, base, elapsed) : 0;
    const std::uint64_t added = emit_added(stats, current, base);

    out.clear();
    bit_writer w(out);
    write_sink sink{w, {}};
    w.put(f::version, f::version_bits);
    w.put(baseline ? 1 : 0, 1);
    if (baseline) w.put_golomb(base.size(), 0);
    w.put(view_checksum(current), f::checksum_bits);
    for (unsigned c = 0; c < f::class_count; ++c) {
        sink.order[c] = stats.best_order(static_cast<f::code_class>(c));
        w.put_golomb(sink.order[c], 0);
    }
    if (baseline) {
        w.put_golomb(touched, 0);
        emit_touched(sink, current, base, elapsed);
    }
    w.put_golomb(added, 0);
    emit_added(sink, current, base);
    w.flush();
}

std::vector<std::uint8_t> encode(view current, std::optional<view> baseline, elapsed_time elapsed) {
    std::vector<std::uint8_t> out;
    encode(current, baseline, elapsed, out);
    return out;
}

std::uint32_t view_checksum(view bodies) noexcept {
    return checksum_of(bodies.size(), [bodies](std::size_t i) -> const quantized_body& { return bodies[i]; });
}

}  // namespace arena::protocol::delta
