// Fuzz target: the UDP connect gate (server/net/udp_connect_gate.hpp), the code that reads a
// raw datagram from anyone before ENet does. The input is a run of datagrams, each as
//   byte 0: source address (low 4 bits: one of 16), bytes 1-2: ms since the previous one
//   (little endian), byte 3: the datagram's length, then that many bytes (fewer at the end);
// fed to three gates: one that remembers every address (to check the rate), one that may keep
// only 4 (to exercise forgetting), and one that requires a connect key. Whatever the bytes, the
// gate must never read past them, admit a connect datagram short enough to be amplified by
// ENet's answer, refuse a datagram addressed to a peer (ENet judges those), admit a non-connect
// addressed to no peer, let an address connect faster than its rate, remember more addresses
// than its limit, or, keyed, admit a connect whose data is not an accepted key; nor may the
// commands of a datagram to a peer (udp_peer_commands.hpp) be read past its end, or pass before
// the peer's Hello and be refused after it.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "server/net/udp_connect_gate.hpp"
#include "server/net/udp_peer_commands.hpp"

namespace {

namespace net = arena::net;

constexpr std::size_t address_count = 16;
constexpr net::connect_gate_limits rate_limits{.connects_per_second = 4, .burst = 16, .max_addresses = 64};
constexpr net::connect_gate_limits small_limits{.connects_per_second = 4, .burst = 16, .max_addresses = 4};

// The keyed gate's clock and keys: window 1000 (and 999) of 300 s windows. Small keys, so
// that a fuzzer finds them in its inputs.
constexpr std::int64_t keyed_unix_seconds = 300'000;
std::uint32_t key_at(std::int64_t unix_seconds) {
    return static_cast<std::uint32_t>(unix_seconds / 300);
}

void check(bool ok) {
    if (!ok) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    net::connect_gate gate(rate_limits), small(small_limits), keyed(rate_limits);
    keyed.require_connect_key(key_at, 300);
    keyed.set_wall_clock(keyed_unix_seconds);
    std::uint64_t passed_keyed = 0;
    std::vector<std::uint64_t> admitted(address_count, 0);
    std::vector<std::int64_t> first_ns(address_count, -1);
    std::int64_t now_ns = 1'000'000'000;
    std::uint64_t datagrams = 0, passed = 0;
    std::size_t at = 0;
    while (at + 4 <= size) {
        const std::size_t source = data[at] & 0x0F;
        now_ns += static_cast<std::int64_t>(data[at + 1] | (data[at + 2] << 8)) * 1'000'000;
        const std::size_t length = std::min<std::size_t>(data[at + 3], size - at - 4);
        // A copy of exactly the datagram's bytes: ASan sees any read past its end.
        const std::vector<std::uint8_t> datagram(data + at + 4, data + at + 4 + length);
        at += 4 + length;
        const std::string address = "10.0.0." + std::to_string(source);

        const net::datagram_kind kind = net::classify_datagram(datagram);
        (void)net::classify_datagram(datagram, true);
        const bool in = gate.admit(datagram, address, now_ns);
        const bool in_small = small.admit(datagram, address, now_ns);
        const bool in_keyed = keyed.admit(datagram, address, now_ns);
        passed_keyed += in_keyed ? 1 : 0;
        const std::optional<std::uint32_t> data = net::connect_data(datagram);
        if (kind != net::datagram_kind::connect) check(!data);
        if (kind == net::datagram_kind::connect && datagram.size() >= net::min_connect_datagram)
            check(data.has_value());
        ++datagrams;
        passed += in ? 1 : 0;
        switch (kind) {
            case net::datagram_kind::peer: {
                check(in && in_small && in_keyed);
                // What a peer may send before its Hello it may send after.
                const bool before = gate.judge_peer(datagram, false) == net::gate_verdict::pass;
                const bool after = gate.judge_peer(datagram, true) == net::gate_verdict::pass;
                if (before) check(after);
                break;
            }
            case net::datagram_kind::too_short:
            case net::datagram_kind::not_a_peer:
                check(!in && !in_small && !in_keyed);
                break;
            case net::datagram_kind::connect:
                if (datagram.size() < net::min_connect_datagram) check(!in && !in_small && !in_keyed);
                if (in_keyed) check(data == key_at(keyed_unix_seconds) || data == key_at(keyed_unix_seconds - 300));
                if (in) {
                    if (first_ns[source] < 0) first_ns[source] = now_ns;
                    ++admitted[source];
                    // Never more than the burst and what the rate refilled since the first.
                    const double refill =
                        static_cast<double>(now_ns - first_ns[source]) * 1e-9 * rate_limits.connects_per_second;
                    check(static_cast<double>(admitted[source]) <= rate_limits.burst + refill + 1e-6);
                }
                break;
        }
        check(gate.addresses() <= address_count);
        check(small.addresses() <= small_limits.max_addresses);
    }
    // Every datagram was admitted or counted refused, for one reason.
    check(passed + gate.refused_rate() + gate.refused_shape() == datagrams);
    check(gate.refused_key() == 0);
    check(passed_keyed + keyed.refused_rate() + keyed.refused_shape() + keyed.refused_key() == datagrams);
    return 0;
}
