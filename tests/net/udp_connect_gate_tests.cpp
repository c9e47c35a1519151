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
