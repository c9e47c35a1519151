// The UDP transport's connect gate (server/net/udp_connect_gate.*): what it reads of a raw
// ENet datagram, and the per-address connect rate, without a socket.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "server/net/udp_connect_gate.hpp"

using namespace arena::net;

namespace {

// An ENet connect datagram as ENet 1.3 sends it: peer id 0xFFF with the sent-time flag, the
// sent time, then the CONNECT command (number 2, acknowledge flag) and its 44 more bytes.
std::vector<uint8_t> connect_datagram(size_t size = min_connect_datagram) {
    std::vector<uint8_t> d(size, 0);
    d[0] = 0x8F;
    d[1] = 0xFF;
    d[4] = 0x82;  // CONNECT | ACKNOWLEDGE
    return d;
}

}  // namespace

TEST_CASE("the gate reads ENet's header: connects, peers, and what is too short", "[net][udp]") {
    CHECK(classify_datagram(std::vector<uint8_t>{}) == datagram_kind::too_short);
    CHECK(classify_datagram(std::vector<uint8_t>{0x8F, 0xFF, 0, 0, 0x82}) == datagram_kind::too_short);
    CHECK(classify_datagram(connect_datagram()) == datagram_kind::connect);
    // Without the sent-time flag the command starts at byte 2.
    CHECK(classify_datagram(std::vector<uint8_t>{0x0F, 0xFF, 0x02, 0, 0, 0}) == datagram_kind::connect);
    // Session bits do not change the peer id.
    CHECK(classify_datagram(std::vector<uint8_t>{0xBF, 0xFF, 0, 0, 0x02, 0, 0, 0}) == datagram_kind::connect);
    // To no peer, but not a connect: ENet ignores it.
    CHECK(classify_datagram(std::vector<uint8_t>{0x8F, 0xFF, 0, 0, 0x06, 0, 0, 0}) == datagram_kind::not_a_peer);
    // To peer 3: ENet checks the slot.
    CHECK(classify_datagram(std::vector<uint8_t>{0x80, 0x03, 0, 0, 0x06, 0, 0, 0}) == datagram_kind::peer);
    // A checksum moves the first command 4 bytes on.
    std::vector<uint8_t> with_checksum = {0x8F, 0xFF, 0, 0, 1, 2, 3, 4, 0x82, 0, 0, 0};
    CHECK(classify_datagram(with_checksum, true) == datagram_kind::connect);
    CHECK(classify_datagram(with_checksum, false) == datagram_kind::not_a_peer);
}

TEST_CASE("the gate allows a burst of connects per address, then its refill rate", "[net][udp]") {
    connect_gate gate({.connects_per_second = 4, .burst = 16, .max_addresses = 4096});
    const auto d = connect_datagram();
    int admitted = 0;
    for (int i = 0; i < 100; ++i) admitted += gate.admit(d, "10.0.0.1", 0) ? 1 : 0;
    CHECK(admitted == 16);
    CHECK(gate.refused_rate() == 84);
    // Another address has its own bucket.
    CHECK(gate.admit(d, "10.0.0.2", 0));
    // A second later, four more.
    admitted = 0;
    for (int i = 0; i < 10; ++i) admitted += gate.admit(d, "10.0.0.1", 1'000'000'000) ? 1 : 0;
    CHECK(admitted == 4);
    // Datagrams to peers are never rate limited here.
    const std::vector<uint8_t> to_peer = {0x80, 0x03, 0, 0, 0x06, 0, 0, 0};
    int passed = 0;
    for (int i = 0; i < 100; ++i) passed += gate.admit(to_peer, "10.0.0.1", 1'000'000'000) ? 1 : 0;
    CHECK(passed == 100);
}

TEST_CASE("the gate refuses connects too short to answer without amplification, and junk to no peer", "[net][udp]") {
    connect_gate gate;
    CHECK_FALSE(gate.admit(connect_datagram(min_connect_datagram - 1), "10.0.0.1", 0));
    CHECK_FALSE(gate.admit(std::vector<uint8_t>{0x8F, 0xFF, 0, 0, 0x06, 0, 0, 0}, "10.0.0.1", 0));
    CHECK_FALSE(gate.admit(std::vector<uint8_t>{1}, "10.0.0.1", 0));
    CHECK(gate.refused_shape() == 3);
    CHECK(gate.refused_rate() == 0);
}

TEST_CASE("a spoofed flood from many addresses costs bounded memory", "[net][udp]") {
    connect_gate gate({.connects_per_second = 4, .burst = 16, .max_addresses = 1000});
    const auto d = connect_datagram();
    int admitted = 0;
    for (int i = 0; i < 100'000; ++i) {
        const std::string address =
            "10." + std::to_string(i / 65536) + "." + std::to_string(i / 256 % 256) + "." + std::to_string(i % 256);
        admitted += gate.admit(d, address, i) ? 1 : 0;
    }
    CHECK(admitted == 100'000);  // each address's first connect is within its burst
    CHECK(gate.addresses() <= 1000);
}

TEST_CASE("the gate's verdict says why it refused, and which admitted datagrams are connects", "[net][udp]") {
    connect_gate gate({.connects_per_second = 4, .burst = 1, .max_addresses = 16});
    CHECK(gate.judge(std::vector<uint8_t>{0x80, 0x03, 0, 0, 0x06, 0, 0, 0}, "10.0.0.1", 0) == gate_verdict::pass);
    CHECK(gate.judge(connect_datagram(), "10.0.0.1", 0) == gate_verdict::connect);
    CHECK(gate.judge(connect_datagram(), "10.0.0.1", 0) == gate_verdict::refuse_rate);
    CHECK(gate.judge(connect_datagram(min_connect_datagram - 1), "10.0.0.2", 0) == gate_verdict::refuse_shape);
    CHECK(gate.judge(std::vector<uint8_t>{1}, "10.0.0.2", 0) == gate_verdict::refuse_shape);
}

namespace {

// A stand-in for auth::token_secret::connect_key over 300 s windows: a distinct key per window.
std::uint32_t test_key_at(std::int64_t unix_seconds) {
    const std::int64_t window = unix_seconds / 300;
    return static_cast<std::uint32_t>(0x9E3779B9u * static_cast<std::uint32_t>(window + 1));
}

// A connect datagram whose CONNECT data is `key`, network byte order, as ENet writes it.
std::vector<uint8_t> connect_with_key(std::uint32_t key) {
    auto d = connect_datagram();
    d[4 + 44] = static_cast<uint8_t>(key >> 24);
    d[4 + 45] = static_cast<uint8_t>(key >> 16);
    d[4 + 46] = static_cast<uint8_t>(key >> 8);
    d[4 + 47] = static_cast<uint8_t>(key);
    return d;
}

}  // namespace

TEST_CASE("the gate reads a connect's data where ENet writes it: the CONNECT command's last 4 bytes", "[net][udp]") {
    CHECK(connect_data(connect_with_key(0x01020304)) == 0x01020304u);
    CHECK(connect_data(connect_datagram()) == 0u);
    // Without the sent-time flag the command, and so its data, starts 2 bytes earlier.
    std::vector<uint8_t> short_header(2 + 48, 0);
    short_header[0] = 0x0F;
    short_header[1] = 0xFF;
    short_header[2] = 0x82;
    short_header[2 + 47] = 0x2A;
    CHECK(connect_data(short_header) == 0x2Au);
    // Not a connect, or one that ends before its data: nothing.
    CHECK_FALSE(connect_data(std::vector<uint8_t>{0x80, 0x03, 0, 0, 0x06, 0, 0, 0}));
    CHECK_FALSE(connect_data(connect_datagram(min_connect_datagram - 1)));
}

TEST_CASE("with a connect key required, a connect passes only with the current or the previous window's key",
          "[net][udp][auth]") {
    connect_gate gate({.connects_per_second = 4, .burst = 100, .max_addresses = 16});
    gate.require_connect_key(test_key_at, 300);
    const std::int64_t now = 1'800'000'000 + 10;  // 10 s into a window
    gate.set_wall_clock(now);
    CHECK(gate.judge(connect_with_key(test_key_at(now)), "10.0.0.1", 0) == gate_verdict::connect);
    // A key minted in the previous window is still good; two windows back it is not.
    CHECK(gate.judge(connect_with_key(test_key_at(now - 300)), "10.0.0.1", 0) == gate_verdict::connect);
    CHECK(gate.judge(connect_with_key(test_key_at(now - 600)), "10.0.0.1", 0) == gate_verdict::refuse_key);
    // A missing key (ENet's default data, 0), a wrong one, and the next window's are refused.
    CHECK(gate.judge(connect_datagram(), "10.0.0.1", 0) == gate_verdict::refuse_key);
    CHECK(gate.judge(connect_with_key(test_key_at(now) ^ 1), "10.0.0.1", 0) == gate_verdict::refuse_key);
    CHECK(gate.judge(connect_with_key(test_key_at(now + 300)), "10.0.0.1", 0) == gate_verdict::refuse_key);
    CHECK(gate.refused_key() == 4);
    CHECK(gate.refused_rate() == 0);
    // Datagrams to peers are ENet's to judge, key or not.
    CHECK(gate.judge(std::vector<uint8_t>{0x80, 0x03, 0, 0, 0x06, 0, 0, 0}, "10.0.0.1", 0) == gate_verdict::pass);
    // A short connect is still refused for its shape first.
    CHECK(gate.judge(connect_datagram(min_connect_datagram - 1), "10.0.0.1", 0) == gate_verdict::refuse_shape);

    // The clock moves into the next window: the key that was current becomes the previous one.
    gate.set_wall_clock(now + 300);
    CHECK(gate.judge(connect_with_key(test_key_at(now + 300)), "10.0.0.1", 0) == gate_verdict::connect);
    CHECK(gate.judge(connect_with_key(test_key_at(now)), "10.0.0.1", 0) == gate_verdict::connect);
    CHECK(gate.judge(connect_with_key(test_key_at(now - 300)), "10.0.0.1", 0) == gate_verdict::refuse_key);
}

TEST_CASE("the gate derives connect keys once per window, not per datagram", "[net][udp][auth]") {
    connect_gate gate;
    int derived = 0;
    gate.require_connect_key(
        [&](std::int64_t t) {
            ++derived;
            return test_key_at(t);
        },
        300);
    const std::int64_t start = 1'800'000'000;
    for (std::int64_t t = start; t < start + 300; ++t) {
        gate.set_wall_clock(t);
        (void)gate.judge(connect_with_key(test_key_at(t)), "10.0.0." + std::to_string(t % 200), 0);
    }
    CHECK(derived == 2);  // the current window's key and the previous one's
    gate.set_wall_clock(start + 300);
    CHECK(derived == 4);
}

TEST_CASE("a keyless connect flood spends no rate bucket and adds no address to remember", "[net][udp][auth]") {
    connect_gate gate({.connects_per_second = 4, .burst = 2, .max_addresses = 16});
    gate.require_connect_key(test_key_at, 300);
    const std::int64_t now = 1'800'000'000;
    gate.set_wall_clock(now);
    for (int i = 0; i < 1000; ++i) CHECK_FALSE(gate.admit(connect_datagram(), "10.0.0." + std::to_string(i % 250), 0));
    CHECK(gate.refused_key() == 1000);
    CHECK(gate.addresses() == 0);
    // The honest client spoofed by that flood still has its whole burst.
    CHECK(gate.judge(connect_with_key(test_key_at(now)), "10.0.0.1", 0) == gate_verdict::connect);
    CHECK(gate.judge(connect_with_key(test_key_at(now)), "10.0.0.1", 0) == gate_verdict::connect);
}

TEST_CASE("with a connect key required but no clock set yet, every connect is refused", "[net][udp][auth]") {
    connect_gate gate;
    gate.require_connect_key(test_key_at, 300);
    CHECK(gate.judge(connect_with_key(test_key_at(0)), "10.0.0.1", 0) == gate_verdict::refuse_key);
}

TEST_CASE("without a token secret no connect key is checked: any connect data passes", "[net][udp][auth]") {
    connect_gate gate;
    CHECK_FALSE(gate.requires_connect_key());
    gate.set_wall_clock(1'800'000'000);  // no keys to derive: nothing changes
    CHECK(gate.judge(connect_datagram(), "10.0.0.1", 0) == gate_verdict::connect);
    CHECK(gate.judge(connect_with_key(0xDEADBEEF), "10.0.0.2", 0) == gate_verdict::connect);
    CHECK(gate.refused_key() == 0);
}
