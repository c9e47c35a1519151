#pragma once
// The file a fuzz target writes each input to when the code under test reads files: one per
// process, in /tmp, removed when the process ends (a run of the corpus used to leave one behind
// per process, thousands over a machine's life).
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <span>
#include <string>

namespace arena::fuzz {

class scratch_file {
public:
    explicit scratch_file(const std::string& stem)
        : path_("/tmp/" + stem + "-" + std::to_string(::getpid()) + ".bin") {}
    ~scratch_file() { std::remove(path_.c_str()); }
    scratch_file(const scratch_file&) = delete;
    scratch_file& operator=(const scratch_file&) = delete;

    // Replaces the file's contents with `bytes`; false when it cannot be written.
    bool write(std::span<const uint8_t> bytes) const {
        FILE* f = std::fopen(path_.c_str(), "wb");
        if (!f) return false;
        const bool whole = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
        return std::fclose(f) == 0 && whole;
    }
    const std::string& path() const { return path_; }

private:
    std::string path_;
};

}  // namespace arena::fuzz
