#pragma once
// Files for the replay tests: unique temporary paths (ctest runs test cases in parallel
// processes), whole-file bytes, and where each record of a file starts.
#include <cstdint>
#include <string>
#include <vector>

namespace arena::replay::testing {

// The golden recording in tests/data.
std::string golden_path();

// A path in the temp directory, unique to this process and `name`; removed at destruction.
class temp_file {
public:
    explicit temp_file(const std::string& name);
    ~temp_file();
    temp_file(const temp_file&) = delete;
    temp_file& operator=(const temp_file&) = delete;
    const std::string& path() const { return path_; }

private:
    std::string path_;
};

std::vector<uint8_t> read_bytes(const std::string& path);
void write_bytes(const std::string& path, const std::vector<uint8_t>& bytes);

// Offsets of the records of a well-formed file, walking the length prefixes.
std::vector<uint64_t> record_offsets(const std::vector<uint8_t>& bytes);

}  // namespace arena::replay::testing
