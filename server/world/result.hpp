#pragma once
// A value or the reason there is none: the one shape every library returns when something can
// fail for a reason a person should read (a config field, a token, a frame, a replay file, a
// polygon). Bytes from a peer or a file never assert or throw; they produce a reason that
// reaches the log, the command line or the peer (Reject/Bye). The match's refusals of a
// client are the one typed exception: a `rejection` carries the RejectCode the client reads
// (server/match/admission.hpp).
// It lives beside the world, the lowest layer, so that every library can use it (as
// assert.hpp); it includes nothing but <string> and <utility>.
#include <string>
#include <utility>

namespace arena {

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

}  // namespace arena
