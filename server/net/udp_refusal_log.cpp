#include "server/net/udp_refusal_log.hpp"

namespace arena::net {

namespace {

std::string_view explain(udp_refusal why) {
    switch (why) {
        case udp_refusal::shape:
            return "not an ENet connect, or one too short to answer";
        case udp_refusal::rate:
            return "over its address's connect rate";
        case udp_refusal::peer_limit:
            return "every peer slot is taken";
    }
    return "?";
}

}  // namespace

std::string_view udp_refusal_key(udp_refusal why) {
    switch (why) {
        case udp_refusal::shape:
            return "shape";
        case udp_refusal::rate:
            return "rate";
        case udp_refusal::peer_limit:
            return "peer_limit";
    }
    return "?";
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
    line += explain(why);
    if (state.silent > 0) {
        line += " (and " + std::to_string(state.silent) + " more for that reason since the last such line)";
    }
    state = {true, now_ns, 0};
    return line;
}

}  // namespace arena::net
