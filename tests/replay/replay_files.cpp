#include "replay_files.hpp"

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "server/world/little_endian.hpp"

namespace arena::replay::testing {

std::string golden_path() {
    return std::string(ARENA_TEST_DATA_DIR) + "/golden_asteroids.arpl";
}

temp_file::temp_file(const std::string& name)
    : path_((std::filesystem::temp_directory_path() /
             ("arena_replay_" + std::to_string(::getpid()) + "_" + name + ".arpl"))
                .string()) {}

temp_file::~temp_file() {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
}

std::vector<uint8_t> read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::vector<uint8_t>& bytes) {
    // Remove, not truncate: ext4 (auto_da_alloc) flushes a truncated-and-rewritten file to disk
    // on close, which made the byte-by-byte tests wait on the disk thousands of times.
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

std::vector<uint64_t> record_offsets(const std::vector<uint8_t>& bytes) {
    std::vector<uint64_t> offsets;
    uint64_t at = 0;
    while (at + 4 <= bytes.size()) {
        offsets.push_back(at);
        const uint32_t length = world::load_le32(bytes.data() + at);
        at += 4 + uint64_t{length} + 4;
    }
    return offsets;
}

}  // namespace arena::replay::testing
