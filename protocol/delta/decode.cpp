// The decoder: reads untrusted bytes. Every count is checked against the limit and against
// the bits left before anything is allocated, every value against its field's range, and
// the result against the checksum the encoder computed.
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <string>

#include "protocol/delta/bits.hpp"
#include "protocol/delta/codec.hpp"
#include "protocol/delta/format.hpp"

namespace arena::protocol::delta {
namespace {

namespace f = format;
using bodies_result = result<std::vector<quantized_body>>;

// The smallest encoding of an added body: id gap, owner, x, y, vx, vy, ω at one bit each
// (order 0) and 16 bits of angle. Bounds the count an honest stream can hold.
constexpr std::uint64_t min_added_bits = 7 + 16;

template <class T>
bool fits(std::int64_t v) noexcept {
    return v >= std::numeric_limits<T>::min() && v <= std::numeric_limits<T>::max();
}

struct header {
    header_info info;
    std::array<unsigned, f::class_count> order{};
};

// Reads the header; an empty string means success.
std::string read_header_into(bit_reader& r, header& h) {
    if (r.get(f::version_bits) != f::version) {
        return r.failed() ? "truncated header" : "unknown delta format version";
    }
    h.info.has_baseline = r.get(1) == 1;
    if (h.info.has_baseline) {
        const std::uint64_t n = r.get_golomb(0);
        if (n > std::numeric_limits<std::uint32_t>::max()) return "baseline count out of range";
        h.info.baseline_count = static_cast<std::uint32_t>(n);
    }
    h.info.checksum = static_cast<std::uint32_t>(r.get(f::checksum_bits));
    for (unsigned& k : h.order) {
        const std::uint64_t v = r.get_golomb(0);
        if (v > max_golomb_order) return "code order out of range";
        k = static_cast<unsigned>(v);
    }
    return r.failed() ? "truncated header" : "";
}

class body_reader {
public:
    body_reader(bit_reader& r, const header& h, elapsed_time e) : r_(r), h_(h), e_(e) {}

    std::uint64_t code(f::code_class c) noexcept { return r_.get_golomb(h_.order[c]); }
    std::int64_t signed_code(f::code_class c) noexcept { return unzigzag(code(c)); }

    // b as predicted, with the changes the stream lists. Empty string: success.
    std::string touched(const quantized_body& b, unsigned mask, quantized_body& out) {
        out = b;
        std::int64_t vx = b.vx, vy = b.vy, w = b.angular_velocity;
        if (mask & f::mask_velocity) {
            vx += signed_code(f::velocity);
            vy += signed_code(f::velocity);
        }
        if (mask & f::mask_angular_velocity) w += signed_code(f::angular_velocity);
        if (!fits<std::int32_t>(vx) || !fits<std::int32_t>(vy)) return "velocity out of range";
        if (!fits<std::int16_t>(w)) return "angular velocity out of range";
        std::int64_t x = b.x + f::predict_displacement(b.vx, vx, e_);
        std::int64_t y = b.y + f::predict_displacement(b.vy, vy, e_);
        std::int64_t da = 0;
        if (mask & f::mask_position) {
            x += signed_code(f::position);
            y += signed_code(f::position);
        }
        if (mask & f::mask_angle) da = signed_code(f::angle);
        if (!fits<std::int32_t>(x) || !fits<std::int32_t>(y)) return "position out of range";
        if (!fits<std::int16_t>(da)) return "angle residual out of range";
        out.vx = static_cast<std::int32_t>(vx);
        out.vy = static_cast<std::int32_t>(vy);
        out.angular_velocity = static_cast<std::int16_t>(w);
        out.x = static_cast<std::int32_t>(x);
        out.y = static_cast<std::int32_t>(y);
        out.angle = f::wrap_angle(b.angle + f::predict_rotation(b.angular_velocity, w, e_) + da);
        return {};
    }

    std::string added(std::uint64_t& next_id, quantized_body& out) {
        const std::uint64_t id = next_id + code(f::id_gap);  // both < 2^62: no overflow
        const std::uint64_t owner = code(f::owner);
        const std::int64_t x = signed_code(f::full_position);
        const std::int64_t y = signed_code(f::full_position);
        const std::int64_t vx = signed_code(f::full_velocity);
        const std::int64_t vy = signed_code(f::full_velocity);
        const auto angle = static_cast<std::uint16_t>(r_.get(16));
        const std::int64_t w = signed_code(f::full_angular_velocity);
        if (r_.failed()) return "truncated added body";
        if (id > std::numeric_limits<std::uint32_t>::max()) return "added body id out of range";
        if (owner > std::numeric_limits<std::uint32_t>::max()) return "owner out of range";
        if (!fits<std::int32_t>(x) || !fits<std::int32_t>(y)) return "position out of range";
        if (!fits<std::int32_t>(vx) || !fits<std::int32_t>(vy)) return "velocity out of range";
        if (!fits<std::int16_t>(w)) return "angular velocity out of range";
        out = quantized_body{static_cast<std::uint32_t>(id),   static_cast<std::uint32_t>(owner),
                             static_cast<std::int32_t>(x),     static_cast<std::int32_t>(y),
                             static_cast<std::int32_t>(vx),    static_cast<std::int32_t>(vy),
                             static_cast<std::int16_t>(angle), static_cast<std::int16_t>(w)};
        next_id = id + 1;
        return {};
    }

private:
    bit_reader& r_;
    const header& h_;
    elapsed_time e_;
};

// The baseline's bodies that stay, in order, into kept. Empty string: success.
std::string read_touched(bit_reader& r, body_reader& br, view base, std::vector<quantized_body>& kept) {
    const std::uint64_t touched = r.get_golomb(0);
    if (r.failed()) return "truncated touched count";
    if (touched > base.size()) return "more touched bodies than the baseline has";
    kept.reserve(base.size());
    quantized_body body;
    std::size_t next = 0;  // the first baseline body not yet decided
    auto keep_unchanged = [&](std::size_t until) {
        for (; next < until; ++next) {
            // mask 0 = exactly as predicted; touched() only fails on ranges, reported below.
            if (const std::string error = br.touched(base[next], 0, body); !error.empty()) return error;
            kept.push_back(body);
        }
        return std::string{};
    };
    for (std::uint64_t t = 0; t < touched; ++t) {
        const std::uint64_t gap = br.code(f::gap);
        if (r.failed()) return "truncated touched body";
        if (gap >= base.size() - next) return "touched body beyond the end of the baseline";
        if (std::string error = keep_unchanged(next + gap); !error.empty()) return error;
        const quantized_body& b = base[next++];
        auto mask = static_cast<unsigned>(r.get(f::mask_bits));
        std::uint32_t owner = b.owner;
        if (mask == 0) {
            if (r.get(1) == 1) continue;  // removed
            const std::uint64_t o = br.code(f::owner);
            if (o > std::numeric_limits<std::uint32_t>::max()) return "owner out of range";
            owner = static_cast<std::uint32_t>(o);
            mask = static_cast<unsigned>(r.get(f::mask_bits));
        }
        if (std::string error = br.touched(b, mask, body); !error.empty()) return error;
        if (r.failed()) return "truncated touched body";
        body.owner = owner;
        kept.push_back(body);
    }
    return keep_unchanged(base.size());
}

}  // namespace

result<header_info> read_header(std::span<const std::uint8_t> bytes) {
    bit_reader r(bytes);
    header h;
    if (std::string error = read_header_into(r, h); !error.empty()) {
        return result<header_info>::failure(std::move(error));
    }
    return result<header_info>::success(h.info);
}

result<std::vector<quantized_body>> decode(std::span<const std::uint8_t> bytes, std::optional<view> baseline,
                                           elapsed_time elapsed, const decode_limits& limits) {
    bit_reader r(bytes);
    header h;
    if (std::string error = read_header_into(r, h); !error.empty()) {
        return bodies_result::failure(std::move(error));
    }
    if (elapsed.tick_rate == 0) return bodies_result::failure("tick rate 0");
    body_reader br(r, h, elapsed);

    std::vector<quantized_body> kept;
    if (h.info.has_baseline) {
        if (!baseline) return bodies_result::failure("a delta needs a baseline, and none is held");
        if (baseline->size() != h.info.baseline_count) {
            return bodies_result::failure("baseline differs from the encoder's (body count)");
        }
        if (baseline->size() > limits.max_bodies) return bodies_result::failure("baseline over the body limit");
        if (std::string error = read_touched(r, br, *baseline, kept); !error.empty()) {
            return bodies_result::failure(std::move(error));
        }
    }

    const std::uint64_t added = r.get_golomb(0);
    if (r.failed()) return bodies_result::failure("truncated added count");
    if (added > limits.max_bodies || kept.size() + added > limits.max_bodies) {
        return bodies_result::failure("more bodies than the limit");
    }
    if (added > r.bits_left() / min_added_bits) {
        return bodies_result::failure("added count larger than the bytes can hold");
    }

    // Merge the kept baseline bodies and the added ones (each sorted) into one sorted view;
    // an added id equal to a kept one, or out of order, is malformed.
    std::vector<quantized_body> out;
    out.reserve(kept.size() + static_cast<std::size_t>(added));
    std::size_t i = 0;
    std::uint64_t next_id = 0;
    quantized_body body;
    for (std::uint64_t a = 0; a < added; ++a) {
        if (std::string error = br.added(next_id, body); !error.empty()) {
            return bodies_result::failure(std::move(error));
        }
        while (i < kept.size() && kept[i].id < body.id) out.push_back(kept[i++]);
        if (i < kept.size() && kept[i].id == body.id) {
            return bodies_result::failure("added body id already in the view");
        }
        out.push_back(body);
    }
    while (i < kept.size()) out.push_back(kept[i++]);

    if (!r.at_clean_end()) return bodies_result::failure("bytes after the end of the delta");
    if (view_checksum(out) != h.info.checksum) {
        return bodies_result::failure("checksum mismatch: wrong baseline or corrupted delta");
    }
    return bodies_result::success(std::move(out));
}

}  // namespace arena::protocol::delta
