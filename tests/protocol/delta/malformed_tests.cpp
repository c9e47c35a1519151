// Refusals: the decoder takes bytes from the network. Every truncation of a valid delta is
// refused; flipped bits and bytes are refused or decode to some valid view, never crash or
// trip a sanitizer; each reason on the list in codec.hpp has a hand-made stream that earns it.
#include <catch2/catch.hpp>

#include <optional>
#include <string>
#include <vector>

#include "protocol/delta/bits.hpp"
#include "protocol/delta/codec.hpp"
#include "protocol/delta/format.hpp"
#include "scenes.hpp"

namespace ad = arena::protocol::delta;
namespace f = arena::protocol::delta::format;
using ad::test::rng;

namespace {

struct fixture {
    std::vector<ad::quantized_body> base, cur;
    ad::elapsed_time e{3, 60};
    fixture() {
        rng r(21);
        auto bodies = ad::test::make_bodies(r, ad::test::motion::drift, 40, 400);
        auto players = ad::test::make_bodies(r, ad::test::motion::player, 20, 400, 100);
        bodies.insert(bodies.end(), players.begin(), players.end());
        base = ad::test::quantize_view(bodies);
        for (int t = 0; t < 3; ++t) ad::test::step(bodies, r, 1.0f / 60);
        bodies.erase(bodies.begin() + 5);                                                      // one leaves
        bodies.push_back(ad::test::make_bodies(r, ad::test::motion::player, 1, 400, 500)[0]);  // one joins
        cur = ad::test::quantize_view(bodies);
    }
};

// A header as the encoder writes it, every class at order 0; the caller writes the rest.
void put_header(ad::bit_writer& w, std::optional<std::size_t> baseline_count, std::uint32_t checksum) {
    w.put(f::version, f::version_bits);
    w.put(baseline_count ? 1 : 0, 1);
    if (baseline_count) w.put_golomb(*baseline_count, 0);
    w.put(checksum, f::checksum_bits);
    for (unsigned c = 0; c < f::class_count; ++c) w.put_golomb(0, 0);
}

void put_added(ad::bit_writer& w, std::uint64_t id_gap, std::int64_t x = 0) {
    w.put_golomb(id_gap, 0);  // id gap
    w.put_golomb(0, 0);       // owner
    w.put_golomb(ad::zigzag(x), 0);
    w.put_golomb(0, 0);
    w.put_golomb(0, 0);
    w.put_golomb(0, 0);
    w.put(0, 16);        // angle
    w.put_golomb(0, 0);  // ω
}

std::string refusal(const std::vector<std::uint8_t>& bytes, std::optional<ad::view> baseline,
                    ad::elapsed_time e = {3, 60}, ad::decode_limits limits = {}) {
    const auto r = ad::decode(bytes, baseline, e, limits);
    return r.ok() ? std::string("accepted") : r.error;
}

}  // namespace

TEST_CASE("Every truncation of a valid delta and of a full snapshot is refused", "[protocol][delta]") {
    const fixture fx;
    for (const bool full : {false, true}) {
        const std::optional<ad::view> baseline = full ? std::nullopt : std::optional<ad::view>(fx.base);
        const auto bytes = ad::encode(fx.cur, baseline, fx.e);
        REQUIRE(ad::decode(bytes, baseline, fx.e).ok());
        for (std::size_t n = 0; n < bytes.size(); ++n) {
            const std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(n));
            INFO("full " << full << ", " << n << " of " << bytes.size() << " bytes");
            REQUIRE(!ad::decode(cut, baseline, fx.e).ok());
        }
    }
}

TEST_CASE("Flipped bits and bytes are refused or decode to a sorted view, never crash", "[protocol][delta]") {
    const fixture fx;
    rng r(22);
    std::size_t refused = 0, accepted = 0;
    for (const bool full : {false, true}) {
        const std::optional<ad::view> baseline = full ? std::nullopt : std::optional<ad::view>(fx.base);
        const auto bytes = ad::encode(fx.cur, baseline, fx.e);
        for (std::size_t i = 0; i < bytes.size() * 8; ++i) {  // every single bit
            auto bad = bytes;
            bad[i / 8] ^= static_cast<std::uint8_t>(1u << (i % 8));
            const auto d = ad::decode(bad, baseline, fx.e);
            ++(d.ok() ? accepted : refused);
        }
        for (int k = 0; k < 5000; ++k) {  // random bytes at random places
            auto bad = bytes;
            const auto flips = 1 + r.below(4);
            for (std::uint64_t j = 0; j < flips; ++j) {
                bad[r.below(bad.size())] ^= static_cast<std::uint8_t>(1 + r.below(255));  // never a no-op
            }
            if (bad == bytes) continue;  // two flips of one byte may cancel
            const auto d = ad::decode(bad, baseline, fx.e);
            if (d.ok()) {
                ++accepted;
                for (std::size_t b = 1; b < d.value.size(); ++b) REQUIRE(d.value[b - 1].id < d.value[b].id);
            } else {
                ++refused;
            }
        }
    }
    INFO("refused " << refused << ", accepted " << accepted);
    CHECK(refused > 0);
    CHECK(accepted == 0);  // the checksum catches what the structure does not (2^-32 odds)
}

TEST_CASE("Random bytes are refused", "[protocol][delta]") {
    const fixture fx;
    rng r(23);
    for (int k = 0; k < 20000; ++k) {
        std::vector<std::uint8_t> junk(r.below(64));
        for (auto& b : junk) b = static_cast<std::uint8_t>(r.next());
        if (!junk.empty() && r.chance(0.5)) junk[0] = static_cast<std::uint8_t>((junk[0] & 0xf0) | f::version);
        REQUIRE(!ad::decode(junk, ad::view(fx.base), fx.e).ok());
    }
}

TEST_CASE("A delta without its baseline, or against a different one, is refused", "[protocol][delta]") {
    const fixture fx;
    const auto bytes = ad::encode(fx.cur, ad::view(fx.base), fx.e);
    CHECK(refusal(bytes, std::nullopt) == "a delta needs a baseline, and none is held");
    CHECK(refusal(bytes, ad::view(fx.base).first(fx.base.size() - 1)).find("baseline differs") == 0);
    auto other = fx.base;
    other[3].x += 1;  // same count, one quantum off
    CHECK(refusal(bytes, ad::view(other)).find("checksum mismatch") == 0);
    CHECK(refusal(bytes, ad::view(fx.base), {4, 60}).find("checksum mismatch") == 0);  // wrong elapsed
    CHECK(refusal(bytes, ad::view(fx.base), {3, 0}) == "tick rate 0");
    // A full snapshot needs none and ignores one.
    const auto full = ad::encode(fx.cur, std::nullopt, fx.e);
    CHECK(refusal(full, std::nullopt) == "accepted");
    CHECK(refusal(full, ad::view(fx.cur)) == "accepted");
    const auto info = ad::read_header(full);
    REQUIRE(info.ok());
    CHECK(!info.value.has_baseline);
    CHECK(ad::read_header(bytes).value.baseline_count == fx.base.size());
}

TEST_CASE("Trailing bytes or set padding bits are refused", "[protocol][delta]") {
    const fixture fx;
    auto bytes = ad::encode(fx.cur, ad::view(fx.base), fx.e);
    auto longer = bytes;
    longer.push_back(0);
    CHECK(refusal(longer, ad::view(fx.base)) == "bytes after the end of the delta");
    // One body at id 5: 48 + 3 + 27 = 78 bits, so the last byte has two padding bits.
    const std::vector<ad::quantized_body> one{{5, 0, 0, 0, 0, 0, 0, 0}};
    std::vector<std::uint8_t> padded;
    ad::bit_writer w(padded);
    put_header(w, std::nullopt, ad::view_checksum(one));
    w.put_golomb(1, 0);
    put_added(w, 5);
    w.flush();
    REQUIRE(padded.size() == 10);
    REQUIRE(refusal(padded, std::nullopt) == "accepted");
    padded.back() |= 0x80;
    CHECK(refusal(padded, std::nullopt) == "bytes after the end of the delta");
}

TEST_CASE("Hand-made streams earn their reasons", "[protocol][delta]") {
    std::vector<std::uint8_t> out;
    ad::bit_writer w(out);

    SECTION("unknown version") {
        w.put(f::version + 1, f::version_bits);
        w.put(0, 32);
        w.flush();
        CHECK(refusal(out, std::nullopt) == "unknown delta format version");
    }
    SECTION("code order out of range") {
        w.put(f::version, f::version_bits);
        w.put(0, 1);
        w.put(0, 32);
        w.put_golomb(ad::max_golomb_order + 1, 0);
        w.flush();
        CHECK(refusal(out, std::nullopt) == "code order out of range");
    }
    SECTION("an over-long Exp-Golomb code") {
        put_header(w, std::nullopt, 0);
        w.put_wide(0, 64);  // 64 zeros: no code of ours is that long
        w.put(1, 1);
        w.flush();
        CHECK(refusal(out, std::nullopt) == "truncated added count");
    }
    SECTION("added ids out of order") {
        std::vector<ad::quantized_body> two{{5, 0, 0, 0, 0, 0, 0, 0}, {6, 0, 0, 0, 0, 0, 0, 0}};
        put_header(w, std::nullopt, ad::view_checksum(two));
        w.put_golomb(2, 0);
        put_added(w, 5);
        put_added(w, 0);  // id 6: fine
        w.flush();
        CHECK(refusal(out, std::nullopt) == "accepted");
        // Ids can only grow (gaps are unsigned), so "out of order" means a duplicate of a kept id.
        out.clear();
        ad::bit_writer again(out);  // a writer ends with its flush()
        const std::vector<ad::quantized_body> base{{6, 0, 0, 0, 0, 0, 0, 0}};
        put_header(again, base.size(), 0);
        again.put_golomb(0, 0);  // nothing touched: body 6 kept
        again.put_golomb(1, 0);
        put_added(again, 6);  // id 6 again
        again.flush();
        CHECK(refusal(out, ad::view(base)) == "added body id already in the view");
    }
    SECTION("an id beyond 2^32 − 1") {
        put_header(w, std::nullopt, 0);
        w.put_golomb(2, 0);
        put_added(w, 0xffffffffu);
        put_added(w, 0);  // 2^32
        w.flush();
        CHECK(refusal(out, std::nullopt) == "added body id out of range");
    }
    SECTION("a position out of int32") {
        put_header(w, std::nullopt, 0);
        w.put_golomb(1, 0);
        put_added(w, 0, std::int64_t{1} << 31);
        w.flush();
        CHECK(refusal(out, std::nullopt) == "position out of range");
    }
    SECTION("a position residual out of int32") {
        const std::vector<ad::quantized_body> base{{1, 0, 2147483000, 0, 0, 0, 0, 0}};
        put_header(w, base.size(), 0);
        w.put_golomb(1, 0);  // one touched
        w.put_golomb(0, 0);  // gap 0
        w.put(f::mask_position, f::mask_bits);
        w.put_golomb(ad::zigzag(1000), 0);  // x beyond 2^31 − 1
        w.put_golomb(0, 0);
        w.put_golomb(0, 0);  // no added
        w.flush();
        CHECK(refusal(out, ad::view(base)) == "position out of range");
    }
    SECTION("an unchanged body whose prediction leaves int32") {
        const std::vector<ad::quantized_body> base{{1, 0, 2147483000, 0, 256 * 1000, 0, 0, 0}};
        put_header(w, base.size(), 0);
        w.put_golomb(0, 0);  // nothing touched: body 1 moves on by prediction, off the range
        w.put_golomb(0, 0);
        w.flush();
        CHECK(refusal(out, ad::view(base)) == "position out of range");
    }
    SECTION("more touched bodies than the baseline has, or a gap past its end") {
        const std::vector<ad::quantized_body> base{{1, 0, 0, 0, 0, 0, 0, 0}};
        put_header(w, base.size(), 0);
        w.put_golomb(2, 0);
        w.flush();
        CHECK(refusal(out, ad::view(base)) == "more touched bodies than the baseline has");
        out.clear();
        ad::bit_writer again(out);  // a writer ends with its flush()
        put_header(again, base.size(), 0);
        again.put_golomb(1, 0);
        again.put_golomb(1, 0);  // gap 1: the touched body would be the second of one
        again.flush();
        CHECK(refusal(out, ad::view(base)) == "touched body beyond the end of the baseline");
    }
    SECTION("a count over the limit, or more than the bytes can hold") {
        put_header(w, std::nullopt, 0);
        w.put_golomb(1000, 0);
        for (int i = 0; i < 1000; ++i) put_added(w, 0);
        w.flush();
        CHECK(refusal(out, std::nullopt, {3, 60}, ad::decode_limits{999}) == "more bodies than the limit");
        out.clear();
        ad::bit_writer again(out);  // a writer ends with its flush()
        put_header(again, std::nullopt, 0);
        again.put_golomb(std::uint64_t{1} << 30, 0);  // a billion bodies in a few bytes
        again.flush();
        CHECK(refusal(out, std::nullopt, {3, 60}, ad::decode_limits{0xffffffffu}) ==
              "added count larger than the bytes can hold");
    }
}
