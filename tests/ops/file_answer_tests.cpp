// The parts of a file answer that need no socket (server/ops/byte_range.*, file_answer.*): which
// bytes a Range header asks for, and the byte rate every download of a port shares, in virtual
// time.
#include <catch2/catch.hpp>

#include "server/ops/byte_range.hpp"
#include "server/ops/file_answer.hpp"

using namespace arena::ops;
using kind = byte_range::kind;

TEST_CASE("byte ranges: one range is honoured, a list or a malformed header means the whole file", "[ops][http]") {
    auto check = [](std::string_view header, uint64_t size, kind what, uint64_t first, uint64_t length) {
        INFO(header << " of " << size);
        const byte_range r = parse_byte_range(header, size);
        CHECK(r.what == what);
        CHECK(r.first == first);
        CHECK(r.length == length);
    };
    check("", 1000, kind::whole, 0, 1000);
    check("bytes=0-99", 1000, kind::partial, 0, 100);
    check("bytes=990-", 1000, kind::partial, 990, 10);
    check("bytes=990-5000", 1000, kind::partial, 990, 10);  // the end is clamped to the file
    check("bytes=-10", 1000, kind::partial, 990, 10);
    check("bytes=-5000", 1000, kind::partial, 0, 1000);
    check("bytes=1000-", 1000, kind::unsatisfiable, 0, 0);
    check("bytes=-0", 1000, kind::unsatisfiable, 0, 0);
    check("bytes=0-", 0, kind::unsatisfiable, 0, 0);
    // Not honoured: served whole, as RFC 9110 allows.
    check("bytes=0-1,5-6", 1000, kind::whole, 0, 1000);
    check("bytes=5-1", 1000, kind::whole, 0, 1000);
    check("bytes=a-b", 1000, kind::whole, 0, 1000);
    check("bytes=+1-2", 1000, kind::whole, 0, 1000);
    check("items=0-1", 1000, kind::whole, 0, 1000);
    check("bytes=99999999999999999999-", 1000, kind::whole, 0, 1000);
}

TEST_CASE("the file pacer lets a port's downloads through at its byte rate, after a short burst", "[ops][http]") {
    file_pacer pacer(1 << 20);  // 1 MiB/s
    const int64_t start = 10'000'000'000;
    int64_t now = start, waited = 0;
    // 64 chunks of 64 KiB (4 MiB) from one moment: the last waits about 4 s, less the 0.1 s burst.
    for (int i = 0; i < 64; ++i) waited = pacer.reserve(now, 64 * 1024);
    CHECK(waited > 3'700'000'000);
    CHECK(waited < 4'000'000'000);
    // Idle for a long time: a burst of only 0.1 s is saved up, not the whole idle time.
    now = start + 100'000'000'000;
    CHECK(pacer.reserve(now, 150 * 1024) == 0);
    CHECK(pacer.reserve(now, 64 * 1024) > 0);
    file_pacer unbounded(0);
    CHECK(unbounded.reserve(now, 1 << 30) == 0);
}
