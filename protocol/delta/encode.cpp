// The encoder: two passes over the same emit functions. The first only counts how long each
// class's values are, to pick each class's Exp-Golomb order; the second writes the bits.
#include <array>
#include <bit>
#include <cassert>
#include <cstdint>

#include "protocol/delta/bits.hpp"
#include "protocol/delta/codec.hpp"
#include "protocol/delta/format.hpp"

namespace arena::protocol::delta {
namespace {

namespace f = format;

[[maybe_unused]] bool strictly_sorted(view v) noexcept {
  for (std::size_t i = 1; i < v.size(); ++i) {
    if (!(v[i - 1].id < v[i].id)) return false;
  }
  return true;
}

// A body present in the baseline and the current view, as the decoder will rebuild it.
struct body_change {
  unsigned mask = 0;
  bool owner_changed = false;
  std::int64_t dvx = 0, dvy = 0, dw = 0, rx = 0, ry = 0, ra = 0;

  [[nodiscard]] bool unchanged() const noexcept { return mask == 0 && !owner_changed; }
};

body_change diff(const quantized_body& b, const quantized_body& c, elapsed_time e) noexcept {
  body_change d;
  d.owner_changed = b.owner != c.owner;
  d.dvx = std::int64_t{c.vx} - b.vx;
  d.dvy = std::int64_t{c.vy} - b.vy;
  d.dw = std::int64_t{c.angular_velocity} - b.angular_velocity;
  d.rx = c.x - (b.x + f::predict_displacement(b.vx, c.vx, e));
  d.ry = c.y - (b.y + f::predict_displacement(b.vy, c.vy, e));
  // The angle residual is the shorter way round the circle: small across the ±π seam too.
  d.ra = f::wrap_angle(std::int64_t{c.angle} -
                       f::wrap_angle(b.angle + f::predict_rotation(b.angular_velocity,
                                                                   c.angular_velocity, e)));
  if (d.dvx != 0 || d.dvy != 0) d.mask |= f::mask_velocity;
  if (d.dw != 0) d.mask |= f::mask_angular_velocity;
  if (d.rx != 0 || d.ry != 0) d.mask |= f::mask_position;
  if (d.ra != 0) d.mask |= f::mask_angle;
  return d;
}

// First pass: how many values of each bit width each class has.
struct stats_sink {
  std::array<std::array<std::uint64_t, 65>, f::class_count> widths{};
  void code(f::code_class c, std::uint64_t n) noexcept { ++widths[c][std::bit_width(n)]; }
  void raw(std::uint64_t, unsigned) noexcept {}

  // The order that makes the class shortest, estimating each value by the smallest of its
  // width (the decoder does not care how the order was chosen).
  [[nodiscard]] unsigned best_order(f::code_class c) const noexcept {
    // Only widths present matter, and no order beyond the widest value can be shorter.
    unsigned widest = 0;
    for (unsigned w = 0; w < 65; ++w) {
      if (widths[c][w] != 0) widest = w;
    }
    unsigned best = 0;
    std::uint64_t best_bits = UINT64_MAX;
    for (unsigned k = 0; k <= widest && k <= max_golomb_order; ++k) {
      std::uint64_t bits = 0;
      for (unsigned w = 0; w <= widest; ++w) {
        if (widths[c][w] == 0) continue;
        const std::uint64_t n = w == 0 ? 0 : std::uint64_t{1} << (w - 1);
        bits += widths[c][w] * golomb_bits(n, k);
      }
      if (bits < best_bits) {
        best_bits = bits;
        best = k;
      }
    }
    return best;
  }
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
      s.raw(0, f::mask_bits);  // escape
      s.raw(1, 1);             // removed
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
    s.code(f::owner, c.owner);
    s.code(f::full_position, zigzag(c.x));
    s.code(f::full_position, zigzag(c.y));
    s.code(f::full_velocity, zigzag(c.vx));
    s.code(f::full_velocity, zigzag(c.vy));
    s.raw(static_cast<std::uint16_t>(c.angle), 16);
    s.code(f::full_angular_velocity, zigzag(c.angular_velocity));
    next_id = std::uint64_t{c.id} + 1;
    ++added;
  }
  return added;
}

}  // namespace

void encode(view current, std::optional<view> baseline, elapsed_time elapsed,
            std::vector<std::uint8_t>& out) {
  assert(strictly_sorted(current) && "views are sorted by strictly increasing id");
  assert((!baseline || strictly_sorted(*baseline)) && "views are sorted by strictly increasing id");
  assert(elapsed.tick_rate > 0);
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

std::vector<std::uint8_t> encode(view current, std::optional<view> baseline,
                                 elapsed_time elapsed) {
  std::vector<std::uint8_t> out;
  encode(current, baseline, elapsed, out);
  return out;
}

std::uint32_t view_checksum(view bodies) noexcept {
  // Four 64-bit words per body through a multiply-rotate mix: a few cycles per body, since
  // the server computes it for every client's view of every snapshot. Not cryptographic.
  constexpr std::uint64_t p1 = 0x9e3779b185ebca87ull;
  constexpr std::uint64_t p2 = 0xc2b2ae3d27d4eb4full;
  std::uint64_t h = 0x27d4eb2f165667c5ull ^ bodies.size();
  auto mix = [&h](std::uint64_t word) {
    h = std::rotl(h ^ (word * p1), 31) * p2;
  };
  for (const quantized_body& b : bodies) {
    mix(std::uint64_t{b.id} | std::uint64_t{b.owner} << 32);
    mix(std::uint64_t{static_cast<std::uint32_t>(b.x)} |
        std::uint64_t{static_cast<std::uint32_t>(b.y)} << 32);
    mix(std::uint64_t{static_cast<std::uint32_t>(b.vx)} |
        std::uint64_t{static_cast<std::uint32_t>(b.vy)} << 32);
    mix(std::uint64_t{static_cast<std::uint16_t>(b.angle)} |
        std::uint64_t{static_cast<std::uint16_t>(b.angular_velocity)} << 16);
  }
  h ^= h >> 29;
  h *= p1;
  h ^= h >> 32;
  return static_cast<std::uint32_t>(h);
}

}  // namespace arena::protocol::delta
