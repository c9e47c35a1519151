// Fuzz target: the replay reader's cost. A replay steps the world once per empty tick up to
// start_tick, then once per Tick record (server/replay/replayer.cpp); every such step is paid
// for either by the bound on start_tick (a minute at the highest tick rate a server runs) or by
// a record of at least 16 bytes of the file. An input that the reader lets through with more
// world steps than that, or with a tick of more joins than a server admits, aborts.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "scratch_file.hpp"
#include "server/replay/reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace arena::replay;
    static const arena::fuzz::scratch_file file("arena-fuzz-replay-cost");
    if (!file.write({data, size})) return 0;
    auto opened = reader::open(file.path());
    if (!opened) return 0;
    reader& r = opened.value;
    constexpr uint64_t smallest_record = record_prefix_size + min_record_body + record_checksum_size;
    const uint64_t budget = max_start_tick(max_tick_rate) + size / smallest_record;
    uint64_t steps = r.file_header().start_tick;
    for (;;) {
        auto e = r.next();
        if (!e) break;
        if (const auto* t = std::get_if<arena::match::tick_record>(&e.value)) {
            ++steps;
            if (t->joins.size() > max_joins_per_tick) std::abort();
        }
        if (steps > budget) std::abort();
        if (std::holds_alternative<end_marker>(e.value)) break;
    }
    return 0;
}
