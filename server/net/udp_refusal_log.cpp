#include "server/net/udp_refusal_log.hpp"

namespace arena::net {

namespace {

// Each reason's key in the counters and its words in the log, indexed by udp_refusal.
struct reason_words {
    std::string_view key;
    std::string_view why;
};
constexpr std::array<reason_words, udp_refusal_reasons> reasons = {{
    {"shape", "not an ENet connect, or one too short to answer"},
    {"rate", "over its address's connect rate"},
    {"peer_limit", "every peer slot is taken"},
    {"connect_key", "a connect without this server's connect key"},
    {"half_open", "no slot free, and its address holds the most half-open handshakes"},
    {"before_hello", "a fragment or a queued command before Hello"},
    {"fragment", "fragments their length does not need"},
}};

}  // namespace

std::string_view udp_refusal_key(udp_refusal why) {
    return reasons[static_cast<std::size_t>(why)].key;
}

std::optional<std::string> udp_refusal_log::refused(udp_refusal why, std::string_view address, int64_t now_ns) {
    reason_state& state = reasons_[static_cast<std::size_t>(why)];
    if (state.logged && now_ns - state.logged_ns < interval_ns_) {
        ++state.silent;
        return std::nullopt;
    }
    std::string line = "udp: refused a datagram from ";
    line += address;
    line += ": ";
    line += reasons[static_cast<std::size_t>(why)].why;
    if (state.silent > 0) {
        line += " (and " + std::to_string(state.silent) + " more for that reason since the last such line)";
    }
    state = {true, now_ns, 0};
    return line;
}

}  // namespace arena::net
