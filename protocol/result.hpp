#pragma once
// The protocol's decoders return arena::result (server/world/result.hpp), the one value-or-reason
// shape of every library; protocol::result names the same template.
#include "server/world/result.hpp"

namespace arena::protocol {

using ::arena::result;

}  // namespace arena::protocol
