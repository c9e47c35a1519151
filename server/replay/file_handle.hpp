#pragma once
// A C stdio file that closes itself. stdio rather than iostreams: its errors come with errno,
// and fflush says exactly when bytes have left the process.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

namespace arena::replay {

struct file_closer {
    void operator()(std::FILE* f) const noexcept { std::fclose(f); }
};
using file_handle = std::unique_ptr<std::FILE, file_closer>;

// "<path>: <what>: <strerror(errno)>", for the failure just reported by stdio.
inline std::string io_error(const std::string& path, const char* what) {
    const int e = errno;
    return path + ": " + what + ": " + (e ? std::strerror(e) : "unknown error");
}

}  // namespace arena::replay
