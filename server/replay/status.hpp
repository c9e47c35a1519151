#pragma once
// Small result helpers shared by the replay code.
#include <type_traits>
#include <utility>
#include <variant>

#include "protocol/result.hpp"

namespace arena::replay {

// The outcome of an operation that has no value: ok, or the reason it failed.
using status = protocol::result<std::monostate>;

inline status ok_status() {
    return status::success({});
}

// A successful result<Variant> holding `alt`, built in place. Why not result::success(alt):
// moving the temporary variant it makes draws a false -Wmaybe-uninitialized from g++ 12 with
// sanitizers, which -Werror (CI) turns into a broken build.
template <class Variant, class Alt>
protocol::result<Variant> success_as(Alt&& alt) {
    protocol::result<Variant> r;
    r.value.template emplace<std::decay_t<Alt>>(std::forward<Alt>(alt));
    return r;
}

}  // namespace arena::replay
