#pragma once
// ARENA_ASSERT(condition, message): a precondition of our own code, checked in Debug builds
// and in the sanitizer build (ARENA_ASSERTS=1, set by CMake) and compiled out in Release, where
// the condition is not even evaluated. A failure prints the file, the line, the condition and
// the message, then aborts. It is for our bugs only: bytes from a peer or a file never reach an
// assert; they are checked where they enter and refused with a reason (STYLE.md, "Errors").
// It lives beside the world, the lowest layer, so that every library can use it; it includes
// nothing but <cstdio> and <cstdlib>.

#if defined(ARENA_ASSERTS) && ARENA_ASSERTS

#include <cstdio>
#include <cstdlib>

namespace arena::detail {
[[noreturn]] inline void assert_failed(const char* file, int line, const char* condition, const char* message) {
    std::fprintf(stderr, "%s:%d: assertion failed: %s: %s\n", file, line, condition, message);
    std::abort();
}
}  // namespace arena::detail

#define ARENA_ASSERT(condition, message) \
    ((condition) ? static_cast<void>(0) : ::arena::detail::assert_failed(__FILE__, __LINE__, #condition, message))

#else

// sizeof keeps the condition compiled (names checked, no unused-variable warnings) but never
// evaluated.
#define ARENA_ASSERT(condition, message) static_cast<void>(sizeof(static_cast<bool>(condition)))

#endif
