#pragma once
// What the UDP transport logs of the datagrams it refuses before ENet reads them. Refusals come
// in floods (a spoofed connect storm, a port scan), so each reason logs at most one line per
// interval: the first refusal at once, then the next one after the interval, with how many were
// refused for that reason in between. The counters (/metrics, --stats-json) count every one.
//
// Plain C++ with the time handed in, so that it is tested without a socket or a clock.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace arena::net {

enum class udp_refusal : std::uint8_t {
    shape,         // too short, a connect too small to answer, or not a connect though to no peer
    rate,          // a connect over its address's rate
    peer_limit,    // a connect while every ENet peer slot is taken
    connect_key,   // a connect without the server's connect key (only with a token secret)
    half_open,     // no slot free, and the address holds the most half-open handshakes
    before_hello,  // to a peer that said no Hello: a fragment or a command ENet would hold
    fragment,      // a fragment claiming more fragments or bytes than its length allows
};
inline constexpr std::size_t udp_refusal_reasons = 7;

// The key of a reason in the counters ("shape", "rate", "peer_limit", "connect_key", "half_open",
// "before_hello", "fragment").
[[nodiscard]] std::string_view udp_refusal_key(udp_refusal why);

class udp_refusal_log {
public:
    explicit udp_refusal_log(int64_t interval_ns = 10'000'000'000) : interval_ns_(interval_ns) {}

    // Notes one refusal of a datagram from `address`. Returns the line to log, when one is due.
    [[nodiscard]] std::optional<std::string> refused(udp_refusal why, std::string_view address, int64_t now_ns);

private:
    struct reason_state {
        bool logged = false;    // a line was logged for this reason
        int64_t logged_ns = 0;  // when
        uint64_t silent = 0;    // refused since, not logged
    };

    int64_t interval_ns_;
    std::array<reason_state, udp_refusal_reasons> reasons_{};
};

}  // namespace arena::net
