#pragma once
// What the UDP transport checks in a raw datagram before ENet reads it. ENet has no handshake
// cookie: a connect command takes a peer slot at once and is answered, so connect-shaped
// datagrams are gated here, per source address, before ENet allocates anything.
//
// With a token secret, a connect must also carry the server's connect key in its CONNECT data
// (auth::token_secret::connect_key): a flood by anyone who was never given the key takes no
// peer slot and no rate bucket.
//
// Plain C++ over bytes (no ENet, no sockets, no clock, no cryptography: the caller hands the
// time and the key derivation in), so it is unit-tested and fuzzed without a network.
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>

#include "server/match/token_bucket.hpp"

namespace arena::net {

// The first bytes of an ENet 1.3 datagram, as far as the gate needs them.
enum class datagram_kind : std::uint8_t {
    too_short,   // shorter than ENet's header and one command header: ENet would drop it too
    connect,     // addressed to no peer yet (peer id 0xFFF) with a CONNECT command first
    not_a_peer,  // addressed to no peer yet, but no CONNECT first: ENet ignores it; so do we
    peer,        // addressed to a peer slot: ENet checks the slot, its address and its session
};

// Reads only the fixed header (peer id, flags, optional sent time) and the first command's
// number. `checksum`: the host adds a 4-byte checksum after the header (we do not).
[[nodiscard]] datagram_kind classify_datagram(std::span<const std::uint8_t> datagram, bool checksum = false);

// The 32 bits of user data of the CONNECT command that starts a connect datagram (ENet 1.3's
// ENetProtocolConnect.data: the command's last 4 bytes, network byte order), or nothing when
// the datagram is not a connect or ends before them.
[[nodiscard]] std::optional<std::uint32_t> connect_data(std::span<const std::uint8_t> datagram, bool checksum = false);

// The bytes of an ENet CONNECT datagram without a checksum: 4 header bytes and the 48-byte
// command. A shorter one is refused, so that the 48-byte VERIFY_CONNECT sent back is never
// larger than what came in (no amplification from a spoofed source).
inline constexpr std::size_t min_connect_datagram = 4 + 48;

// What the gate decided about one datagram, and why when it refused.
enum class gate_verdict : std::uint8_t {
    pass,                 // to a peer slot: ENet judges it
    connect,              // a connect within its address's rate: ENet takes a peer slot for it, if one is free
    refuse_shape,         // too short, a connect too small to answer, or not a connect though to no peer
    refuse_rate,          // a connect over its address's rate
    refuse_key,           // a connect without an accepted connect key, when keys are required
    refuse_before_hello,  // to a peer that said no Hello: a fragment or a command ENet would hold
    refuse_fragment,      // to a peer: a fragment claiming more than its length (or a client frame) allows
};

struct connect_gate_limits {
    double connects_per_second = 4;  // per source address, after the burst
    double burst = 16;
    std::size_t max_addresses = 4096;  // remembered at once; beyond it the oldest half is forgotten
};

// Per-address connect rate. Each datagram that would create a peer takes one token of its
// address's bucket; an address without tokens is ignored until they refill.
class connect_gate {
public:
    explicit connect_gate(connect_gate_limits limits = {}) : limits_(limits) {}

    // pass or connect: hand the datagram to ENet. `address`: the source without its port (a flood from
    // many ports of one host shares one bucket).
    [[nodiscard]] gate_verdict judge(std::span<const std::uint8_t> datagram, const std::string& address,
                                     int64_t now_ns);
    [[nodiscard]] bool admit(std::span<const std::uint8_t> datagram, const std::string& address, int64_t now_ns) {
        const gate_verdict verdict = judge(datagram, address, now_ns);
        return verdict == gate_verdict::pass || verdict == gate_verdict::connect;
    }

    // From now on a connect must carry in its data the key of the current window or of the one
    // before: `key_at(t)` is the key of the window of `window_s` seconds holding Unix time t.
    // The keys are derived in set_wall_clock, once per window, so judging a connect costs two
    // comparisons. Until the clock is set, every connect is refused.
    void require_connect_key(std::function<std::uint32_t(std::int64_t unix_seconds)> key_at, std::int64_t window_s);
    // The Unix time (seconds) the keys are accepted for; cheap while the window stays the same.
    void set_wall_clock(std::int64_t unix_seconds);
    bool requires_connect_key() const { return static_cast<bool>(key_at_); }

    // A datagram that judge() passed to a peer slot, by its commands (udp_peer_commands.hpp):
    // pass, refuse_before_hello or refuse_fragment. `said_hello`: the peer's Hello reached the match.
    [[nodiscard]] gate_verdict judge_peer(std::span<const std::uint8_t> datagram, bool said_hello);

    std::uint64_t refused_rate() const { return refused_rate_; }
    std::uint64_t refused_shape() const { return refused_shape_; }
    std::uint64_t refused_key() const { return refused_key_; }
    std::uint64_t refused_before_hello() const { return refused_before_hello_; }
    std::uint64_t refused_fragment() const { return refused_fragment_; }
    std::size_t addresses() const { return buckets_.size(); }

private:
    void forget_oldest();
    bool carries_accepted_key(std::span<const std::uint8_t> datagram) const;

    connect_gate_limits limits_;
    std::unordered_map<std::string, match::token_bucket> buckets_;
    std::uint64_t refused_rate_ = 0;   // connects over an address's rate
    std::uint64_t refused_shape_ = 0;  // too short, or no connect though addressed to no peer
    std::uint64_t refused_key_ = 0;    // connects without an accepted key
    std::uint64_t refused_before_hello_ = 0;
    std::uint64_t refused_fragment_ = 0;

    std::function<std::uint32_t(std::int64_t)> key_at_;  // empty: no key required
    std::int64_t window_s_ = 1;
    std::optional<std::int64_t> keys_window_;       // the window accepted_keys_ were derived for
    std::array<std::uint32_t, 2> accepted_keys_{};  // the current window's and the previous one's
};

}  // namespace arena::net
