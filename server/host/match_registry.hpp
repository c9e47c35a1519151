#pragma once
// The matches this process hosts, by id. Today there is one, the default, and every
// connection belongs to it; a later change hosts many. The intake and the transports already
// ask here for a connection's match instead of holding one, so that routing by match id
// changes this file and not them.
#include <cstdint>

#include "server/match/match.hpp"

namespace arena::host {

using match_id = uint32_t;
inline constexpr match_id default_match_id = 0;

class match_registry {
public:
    // `default_match` outlives the registry (the host, or a test, owns it).
    explicit match_registry(match::match& default_match) : default_(default_match) {}

    // The match `id` names; nullptr when this process hosts none by that id.
    match::match* find(match_id id) { return id == default_match_id ? &default_ : nullptr; }
    // The match `c` belongs to: today always the default one.
    match::match& match_of(const match::connection& /*c*/) { return default_; }
    match::match& default_match() { return default_; }
    const match::match& default_match() const { return default_; }

private:
    match::match& default_;
};

}  // namespace arena::host
