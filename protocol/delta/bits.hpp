#pragma once
// Bit packing for the delta codec: bits go into bytes least significant first; integers are
// zigzag-mapped (small magnitudes of either sign → small codes) and written as Exp-Golomb
// codes of order k (a run of zeros, a one, then the rest of the number: about
// 2·log2(n / 2^k) + k + 1 bits, so small values are short and no value is impossible).
// The reader takes untrusted bytes: reading past the end or an over-long code sets a sticky
// failure flag and returns 0, so a decoder checks once per section, never crashes.
#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

namespace arena::protocol::delta {

inline constexpr unsigned max_golomb_order = 24;

[[nodiscard]] constexpr std::uint64_t zigzag(std::int64_t v) noexcept {
    // C++20: >> of a negative value is arithmetic, and the casts are modular.
    return (static_cast<std::uint64_t>(v) << 1) ^ static_cast<std::uint64_t>(v >> 63);
}
[[nodiscard]] constexpr std::int64_t unzigzag(std::uint64_t n) noexcept {
    return static_cast<std::int64_t>((n >> 1) ^ (~(n & 1) + 1));
}

// Bits an Exp-Golomb code of order k takes for n (n < 2^62).
[[nodiscard]] constexpr unsigned golomb_bits(std::uint64_t n, unsigned k) noexcept {
    const auto width = static_cast<unsigned>(std::bit_width(n + (std::uint64_t{1} << k)));
    return 2 * width - 1 - k;
}

// Appends to a vector. The vector is grown ahead and written through a cursor (an insert per
// word was a visible share of the server's encoding); flush() must end every use, as it trims
// the vector to the bytes written.
class bit_writer {
public:
    explicit bit_writer(std::vector<std::uint8_t>& out) : out_(out), pos_(out.size()) {
        out_.resize(pos_ + std::max<std::size_t>(64, out_.capacity() - pos_));
    }

    // n ≤ 32 bits of v (higher bits of v must be 0). Fewer than 32 bits wait in the
    // accumulator between calls; whole 32-bit words go out at once.
    void put(std::uint64_t v, unsigned n) {
        acc_ |= v << used_;
        used_ += n;
        if (used_ >= 32) {
            if (pos_ + 4 > out_.size()) out_.resize(2 * out_.size());
            std::uint8_t* at = out_.data() + pos_;
            at[0] = static_cast<std::uint8_t>(acc_);
            at[1] = static_cast<std::uint8_t>(acc_ >> 8);
            at[2] = static_cast<std::uint8_t>(acc_ >> 16);
            at[3] = static_cast<std::uint8_t>(acc_ >> 24);
            pos_ += 4;
            acc_ >>= 32;
            used_ -= 32;
        }
    }
    void put_wide(std::uint64_t v, unsigned n) {  // n ≤ 64
        while (n > 32) {
            put(v & 0xffffffffu, 32);
            v >>= 32;
            n -= 32;
        }
        put(v, n);
    }
    // Exp-Golomb, order k ≤ max_golomb_order, n < 2^62.
    void put_golomb(std::uint64_t n, unsigned k) {
        const std::uint64_t m = n + (std::uint64_t{1} << k);
        const auto width = static_cast<unsigned>(std::bit_width(m));
        const unsigned zeros = width - 1 - k;
        const std::uint64_t rest = m & ((std::uint64_t{1} << (width - 1)) - 1);
        // The common case in one step: the zeros, the one and the rest are the bits of
        // ((rest << 1) | 1) << zeros. The hot path of the server's snapshots.
        if (zeros + width <= 32) {
            put(((rest << 1) | 1) << zeros, zeros + width);
            return;
        }
        put_wide(0, zeros);
        put(1, 1);
        put_wide(rest, width - 1);
    }
    // Writes the bits still waiting, padding the last byte with zero bits, and trims the
    // vector to what was written.
    void flush() {
        out_.resize(pos_);
        for (; used_ > 0; used_ = used_ > 8 ? used_ - 8 : 0) {
            out_.push_back(static_cast<std::uint8_t>(acc_));
            acc_ >>= 8;
        }
        pos_ = out_.size();
        acc_ = 0;
    }

private:
    std::vector<std::uint8_t>& out_;
    std::uint64_t acc_ = 0;
    unsigned used_ = 0;  // < 32 between calls
    std::size_t pos_;    // bytes written (out_ is larger until flush())
};

class bit_reader {
public:
    explicit bit_reader(std::span<const std::uint8_t> bytes) noexcept : bytes_(bytes) {}

    [[nodiscard]] bool failed() const noexcept { return failed_; }
    [[nodiscard]] std::uint64_t bits_left() const noexcept { return bytes_.size() * 8 - pos_; }

    // n ≤ 32 bits; 0 (and failed) when fewer are left.
    std::uint64_t get(unsigned n) noexcept {
        if (n > bits_left()) return fail();
        const std::uint64_t v = peek(n);
        pos_ += n;
        return v;
    }
    std::uint64_t get_wide(unsigned n) noexcept {  // n ≤ 64
        std::uint64_t v = 0;
        unsigned at = 0;
        while (n > 32) {
            v |= get(32) << at;
            at += 32;
            n -= 32;
        }
        return v | (get(n) << at);
    }
    // Refuses (failed, 0) a code longer than the writer can produce: the result is < 2^62.
    std::uint64_t get_golomb(unsigned k) noexcept {
        // The zeros before the first one bit, counted up to 56 at a time instead of bit by bit:
        // this prefix is in every code, and reading it a bit at a time was most of a decode.
        unsigned zeros = 0;
        for (;;) {
            const unsigned avail = static_cast<unsigned>(std::min<std::uint64_t>(bits_left(), 56));
            if (avail == 0) return fail();  // ran out before the one
            const std::uint64_t w = peek(avail);
            if (w == 0) {
                zeros += avail;
                pos_ += avail;
            } else {
                const auto z = static_cast<unsigned>(std::countr_zero(w));
                zeros += z;
                pos_ += z + 1;  // the zeros and the one
            }
            if (zeros + k > 61) return fail();
            if (w != 0) break;
        }
        const unsigned low = zeros + k;
        const std::uint64_t m = (std::uint64_t{1} << low) | get_wide(low);
        return failed_ ? 0 : m - (std::uint64_t{1} << k);
    }

    // The writer pads with at most 7 zero bits: anything else after the data is malformed.
    [[nodiscard]] bool at_clean_end() noexcept {
        const std::uint64_t left = bits_left();
        return !failed_ && left < 8 && get(static_cast<unsigned>(left)) == 0;
    }

private:
    // The next n ≤ 56 bits (n ≤ bits_left()), without moving: 8 bytes in one load where the
    // buffer has them (a byte at a time was the reader's cost), least significant bit first.
    [[nodiscard]] std::uint64_t peek(unsigned n) const noexcept {
        const std::size_t byte = pos_ >> 3;
        const unsigned shift = pos_ & 7;
        std::uint64_t w = 0;
        if (bytes_.size() - byte >= 8 && std::endian::native == std::endian::little) {
            std::memcpy(&w, bytes_.data() + byte, 8);
        } else {
            const std::size_t avail = std::min<std::size_t>(bytes_.size() - byte, 8);
            for (std::size_t i = 0; i < avail; ++i) w |= std::uint64_t{bytes_[byte + i]} << (8 * i);
        }
        return (w >> shift) & ((std::uint64_t{1} << n) - 1);
    }

    std::uint64_t fail() noexcept {
        failed_ = true;
        pos_ = bytes_.size() * 8;
        return 0;
    }

    std::span<const std::uint8_t> bytes_;
    std::uint64_t pos_ = 0;
    bool failed_ = false;
};

}  // namespace arena::protocol::delta
