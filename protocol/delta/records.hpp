#pragma once
// Internal to the encoders (encode.cpp, shared_encoder.cpp): a body's change against its
// baseline, the records both write, and the two passes' sinks (the first measures each code
// class to pick its Exp-Golomb order, the second writes the bits).
#include <array>
#include <bit>
#include <cstdint>

#include "protocol/delta/bits.hpp"
#include "protocol/delta/codec.hpp"
#include "protocol/delta/format.hpp"

namespace arena::protocol::delta::records {

namespace f = format;

// A body present in the baseline and the current view, as the decoder will rebuild it.
struct body_change {
    unsigned mask = 0;
    bool owner_changed = false;
    std::int64_t dvx = 0, dvy = 0, dw = 0, rx = 0, ry = 0, ra = 0;

    [[nodiscard]] bool unchanged() const noexcept { return mask == 0 && !owner_changed; }
};

inline body_change diff(const quantized_body& b, const quantized_body& c, elapsed_time e) noexcept {
    body_change d;
    d.owner_changed = b.owner != c.owner;
    d.dvx = std::int64_t{c.vx} - b.vx;
    d.dvy = std::int64_t{c.vy} - b.vy;
    d.dw = std::int64_t{c.angular_velocity} - b.angular_velocity;
    d.rx = c.x - (b.x + f::predict_displacement(b.vx, c.vx, e));
    d.ry = c.y - (b.y + f::predict_displacement(b.vy, c.vy, e));
    // The angle residual is the shorter way round the circle: small across the ±π seam too.
    d.ra = f::wrap_angle(std::int64_t{c.angle} -
                         f::wrap_angle(b.angle + f::predict_rotation(b.angular_velocity, c.angular_velocity, e)));
    if (d.dvx != 0 || d.dvy != 0) d.mask |= f::mask_velocity;
    if (d.dw != 0) d.mask |= f::mask_angular_velocity;
    if (d.rx != 0 || d.ry != 0) d.mask |= f::mask_position;
    if (d.ra != 0) d.mask |= f::mask_angle;
    return d;
}

// How many values of each bit width (0..64) one class has. Only the widths present hold a
// count, so a tally needs no clearing and the order's search below visits those alone (a class
// holds a few of the 65): clearing and walking every width of every class was most of a small
// match's encoding.
class width_tally {
public:
    width_tally() noexcept {}  // user-provided: `width_tally t{}` must not clear counts_ either

    void add(std::uint64_t n) noexcept {
        const auto w = static_cast<unsigned>(std::bit_width(n));
        if (has(w)) {
            ++counts_[w];
            return;
        }
        if (w < 64) {
            low_ |= std::uint64_t{1} << w;
        } else {
            top_ = true;
        }
        counts_[w] = 1;
    }
    [[nodiscard]] bool has(unsigned w) const noexcept { return w < 64 ? (low_ >> w & 1) != 0 : top_; }
    // Values of width w; 0 for a width not present.
    [[nodiscard]] std::uint64_t count(unsigned w) const noexcept { return has(w) ? counts_[w] : 0; }
    // The widths present, narrowest first, into `out`; how many there are.
    unsigned present(std::array<unsigned, 65>& out) const noexcept {
        unsigned n = 0;
        for (std::uint64_t bits = low_; bits != 0; bits &= bits - 1)
            out[n++] = static_cast<unsigned>(std::countr_zero(bits));
        if (top_) out[n++] = 64;
        return n;
    }

private:
    std::array<std::uint64_t, 65> counts_;  // left uninitialised: a width is counted from its first value
    std::uint64_t low_ = 0;                 // bit w: width w (below 64) present
    bool top_ = false;                      // width 64 present
};

// The order that makes the class shortest, estimating each value by the smallest of its
// width (the decoder does not care how the order was chosen).
[[nodiscard]] inline unsigned best_order(const width_tally& widths) noexcept {
    // No order beyond the widest value can be shorter.
    std::array<unsigned, 65> present;
    const unsigned count = widths.present(present);
    const unsigned widest = count == 0 ? 0 : present[count - 1];
    unsigned best = 0;
    std::uint64_t best_bits = UINT64_MAX;
    for (unsigned k = 0; k <= widest && k <= max_golomb_order; ++k) {
        std::uint64_t bits = 0;
        for (unsigned i = 0; i < count; ++i) {
            const unsigned w = present[i];
            const std::uint64_t n = w == 0 ? 0 : std::uint64_t{1} << (w - 1);
            bits += widths.count(w) * golomb_bits(n, k);
        }
        if (bits < best_bits) {
            best_bits = bits;
            best = k;
        }
    }
    return best;
}

// First pass: how many values of each bit width each class has.
struct stats_sink {
    std::array<width_tally, f::class_count> widths;
    void code(f::code_class c, std::uint64_t n) noexcept { widths[c].add(n); }
    void raw(std::uint64_t, unsigned) noexcept {}
    [[nodiscard]] unsigned best_order(f::code_class c) const noexcept { return records::best_order(widths[c]); }
};

// Second pass: the bits.
struct write_sink {
    bit_writer& w;
    std::array<unsigned, f::class_count> order{};
    void code(f::code_class c, std::uint64_t n) { w.put_golomb(n, order[c]); }
    void raw(std::uint64_t v, unsigned n) { w.put(v, n); }
};

template <class Sink>
void emit_change(Sink& s, const body_change& d, std::uint32_t owner) {
    if (d.owner_changed) {
        s.raw(0, f::mask_bits);  // escape
        s.raw(0, 1);             // not removed: the owner changed
        s.code(f::owner, owner);
    }
    s.raw(d.mask, f::mask_bits);
    if (d.mask & f::mask_velocity) {
        s.code(f::velocity, zigzag(d.dvx));
        s.code(f::velocity, zigzag(d.dvy));
    }
    if (d.mask & f::mask_angular_velocity) s.code(f::angular_velocity, zigzag(d.dw));
    if (d.mask & f::mask_position) {
        s.code(f::position, zigzag(d.rx));
        s.code(f::position, zigzag(d.ry));
    }
    if (d.mask & f::mask_angle) s.code(f::angle, zigzag(d.ra));
}

// An added body's record after its id gap: owner, position, velocity, angle, spin, in full.
template <class Sink>
void emit_added_fields(Sink& s, const quantized_body& c) {
    s.code(f::owner, c.owner);
    s.code(f::full_position, zigzag(c.x));
    s.code(f::full_position, zigzag(c.y));
    s.code(f::full_velocity, zigzag(c.vx));
    s.code(f::full_velocity, zigzag(c.vy));
    s.raw(static_cast<std::uint16_t>(c.angle), 16);
    s.code(f::full_angular_velocity, zigzag(c.angular_velocity));
}

// A baseline body that left the view: the escape mask, then 1.
template <class Sink>
void emit_removed(Sink& s) {
    s.raw(0, f::mask_bits);
    s.raw(1, 1);
}

// view_checksum() of `count` bodies, body(i) giving the i-th: the encoders checksum a view
// held as a span or as indices into a state.
template <class Body>
std::uint32_t checksum_of(std::size_t count, Body body) noexcept {
    // Four 64-bit words per body through a multiply-rotate mix: a few cycles per body, since
    // the server computes it for every client's view of every snapshot. Not cryptographic.
    constexpr std::uint64_t p1 = 0x9e3779b185ebca87ull;
    constexpr std::uint64_t p2 = 0xc2b2ae3d27d4eb4full;
    std::uint64_t h = 0x27d4eb2f165667c5ull ^ count;
    auto mix = [&h](std::uint64_t word) {
        h = std::rotl(h ^ (word * p1), 31) * p2;
    };
    for (std::size_t i = 0; i < count; ++i) {
        const quantized_body& b = body(i);
        mix(std::uint64_t{b.id} | std::uint64_t{b.owner} << 32);
        mix(std::uint64_t{static_cast<std::uint32_t>(b.x)} | std::uint64_t{static_cast<std::uint32_t>(b.y)} << 32);
        mix(std::uint64_t{static_cast<std::uint32_t>(b.vx)} | std::uint64_t{static_cast<std::uint32_t>(b.vy)} << 32);
        mix(std::uint64_t{static_cast<std::uint16_t>(b.angle)} |
            std::uint64_t{static_cast<std::uint16_t>(b.angular_velocity)} << 16);
    }
    h ^= h >> 29;
    h *= p1;
    h ^= h >> 32;
    return static_cast<std::uint32_t>(h);
}

}  // namespace arena::protocol::delta::records
