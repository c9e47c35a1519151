// Fuzz target: the replay-file reader. The bytes go to a file (the reader reads files), then
// every record is read until the end or the first error.
#include <cstddef>
#include <cstdint>

#include "scratch_file.hpp"
#include "server/replay/reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace arena;
    static const fuzz::scratch_file file("arena-fuzz-replay");
    if (!file.write({data, size})) return 0;
    auto opened = replay::reader::open(file.path());
    if (!opened) return 0;
    replay::reader& r = opened.value;
    for (int records = 0; records < 100000; ++records) {
        auto e = r.next();
        if (!e || std::holds_alternative<replay::end_marker>(e.value)) break;
    }
    return 0;
}
