// Fuzz target: the replay-file reader. The bytes go to a file (the reader reads files), then
// every record is read until the end or the first error.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "server/replay/reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace arena;
    static const std::string path = "/tmp/arena-fuzz-replay-" + std::to_string(::getpid()) + ".bin";
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return 0;
    std::fwrite(data, 1, size, f);
    std::fclose(f);
    auto opened = replay::reader::open(path);
    if (!opened) return 0;
    replay::reader& r = opened.value;
    for (int records = 0; records < 100000; ++records) {
        auto e = r.next();
        if (!e || std::holds_alternative<replay::end_marker>(e.value)) break;
    }
    return 0;
}
