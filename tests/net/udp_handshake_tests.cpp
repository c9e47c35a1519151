// The last step of ENet's handshake (server/net/udp_handshake.*): the acknowledgement of
// VERIFY_CONNECT put in front of a datagram that proves it arrived, over bytes alone.
#include <catch2/catch.hpp>
#include <vector>

#include "server/net/udp_handshake.hpp"

using namespace arena::net;

namespace {

// A Hello as an ENet client sends it right after VERIFY_CONNECT: to peer 5 in session 2, with
// the sent time, one SEND_RELIABLE (command 6, acknowledge flag) on channel 0, 3 bytes of data.
const std::vector<uint8_t> hello_datagram = {0xA0, 0x05, 0x12, 0x34, 0x86, 0x00, 0x00, 0x01, 0x00, 0x03, 'a', 'b', 'c'};

}  // namespace

TEST_CASE("the header of a datagram to a peer: its id, session and size", "[net][udp]") {
    auto header = read_datagram_header(hello_datagram);
    REQUIRE(header);
    CHECK(header->peer_id == 5);
    CHECK(header->session == 2);
    CHECK_FALSE(header->compressed);
    CHECK(header->size == 4);
    header = read_datagram_header(std::vector<uint8_t>{0x4F, 0xFF});
    REQUIRE(header);
    CHECK(header->peer_id == 0xFFF);
    CHECK(header->compressed);
    CHECK(header->size == 2);
    CHECK_FALSE(read_datagram_header(std::vector<uint8_t>{0x80}));
    CHECK_FALSE(read_datagram_header(std::vector<uint8_t>{0x80, 0x05, 0x00}));
}

TEST_CASE("a lost acknowledgement of VERIFY_CONNECT is put in front of the Hello that proves it arrived",
          "[net][udp]") {
    std::vector<uint8_t> out;
    REQUIRE(acknowledge_verify_connect(hello_datagram, {.sequence = 1, .sent_ms = 0x00ABCDEF}, out));
    const std::vector<uint8_t> expected = {
        0xA0, 0x05, 0x12, 0x34,                          // the header as it came
        0x01, 0xFF, 0x00, 0x01, 0x00, 0x01, 0xCD, 0xEF,  // ACKNOWLEDGE of sequence 1 on channel 0xFF, sent at ..CDEF
        0x86, 0x00, 0x00, 0x01, 0x00, 0x03, 'a',  'b',  'c'};
    CHECK(out == expected);
}

TEST_CASE("no acknowledgement is added where ENet needs none or could not read it", "[net][udp]") {
    std::vector<uint8_t> out = {42};
    const unacknowledged_verify verify{.sequence = 1, .sent_ms = 7};
    // The peer's own acknowledgement comes first: ENet completes the handshake itself.
    CHECK_FALSE(acknowledge_verify_connect(
        std::vector<uint8_t>{0xA0, 0x05, 0x12, 0x34, 0x01, 0xFF, 0x00, 0x01, 0x00, 0x01, 0x00, 0x07}, verify, out));
    // Compressed: the commands are not where they seem.
    CHECK_FALSE(
        acknowledge_verify_connect(std::vector<uint8_t>{0xE0, 0x05, 0x12, 0x34, 0x86, 0x00, 0x00, 0x01}, verify, out));
    // A header and no command.
    CHECK_FALSE(acknowledge_verify_connect(std::vector<uint8_t>{0xA0, 0x05, 0x12, 0x34}, verify, out));
    CHECK_FALSE(acknowledge_verify_connect(std::vector<uint8_t>{0xA0}, verify, out));
    CHECK(out == std::vector<uint8_t>{42});
}
