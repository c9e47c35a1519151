#pragma once
// Debian's emscripten 3.1.6 ships a libc++ without std::bit_cast, which the world's hash uses
// (server/world/fnv1a.hpp). The WebAssembly build force-includes this header (-include) to
// supply it from the compiler's builtin, the very thing newer libc++ versions implement it
// with. Nothing is defined where the standard library has its own.
#include <version>
#if !defined(__cpp_lib_bit_cast)
#include <bit>
#include <type_traits>
namespace std {
template <class To, class From>
requires(sizeof(To) == sizeof(From) && is_trivially_copyable_v<To> && is_trivially_copyable_v<From>)
    [[nodiscard]] constexpr To bit_cast(const From& from) noexcept {
    return __builtin_bit_cast(To, from);
}
}  // namespace std
#endif
