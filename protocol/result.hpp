#pragma once
// A value or the reason there is none. Decoders return this for anything a peer sent:
// bytes from the network never assert or throw, they produce a reason that reaches the log
// and the peer (Reject/Bye).
#include <string>
#include <utility>

namespace arena::protocol {

template <class T>
struct result {
    T value{};          // meaningful only when error is empty
    std::string error;  // empty on success; otherwise a specific, human-readable reason

    static result success(T v) { return result{std::move(v), {}}; }
    static result failure(std::string reason) {
        // An empty reason would read as success: never let a caller's slip turn a refusal into one.
        if (reason.empty()) reason = "unspecified error";
        return result{T{}, std::move(reason)};
    }

    [[nodiscard]] bool ok() const noexcept { return error.empty(); }
    explicit operator bool() const noexcept { return ok(); }
};

}  // namespace arena::protocol
