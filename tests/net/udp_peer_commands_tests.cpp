// What a datagram to a peer slot would make ENet hold (server/net/udp_peer_commands.*): the
// fragment bomb of ENet 1.3.17 and what a peer may send before its Hello, without a socket.
#include <catch2/catch.hpp>
#include <cstdint>
#include <vector>

#include "server/net/udp_connect_gate.hpp"
#include "server/net/udp_peer_commands.hpp"

using namespace arena::net;

namespace {

void put_u16(std::vector<uint8_t>& d, uint32_t v) {
    d.push_back(static_cast<uint8_t>(v >> 8));
    d.push_back(static_cast<uint8_t>(v));
}

void put_u32(std::vector<uint8_t>& d, uint32_t v) {
    put_u16(d, v >> 16);
    put_u16(d, v & 0xFFFF);
}

// The header of a datagram to peer 3, session 1, without a sent time.
std::vector<uint8_t> to_peer() {
    return {0x10, 0x03};
}

void add_reliable(std::vector<uint8_t>& d, uint16_t sequence, uint16_t bytes) {
    d.insert(d.end(), {0x86, 0x00});
    put_u16(d, sequence);
    put_u16(d, bytes);
    d.insert(d.end(), bytes, 0x41);
}

void add_fragment(std::vector<uint8_t>& d, uint8_t command, uint16_t sequence, uint16_t bytes, uint32_t count,
                  uint32_t number, uint32_t total) {
    d.insert(d.end(), {command, 0x00});
    put_u16(d, sequence);
    put_u16(d, sequence);
    put_u16(d, bytes);
    put_u32(d, count);
    put_u32(d, number);
    put_u32(d, total);
    put_u32(d, number * bytes);
    d.insert(d.end(), bytes, 0x42);
}

void add_ping(std::vector<uint8_t>& d, uint16_t sequence) {
    d.insert(d.end(), {0x85, 0xFF});
    put_u16(d, sequence);
}

}  // namespace

TEST_CASE("the fragment bomb of ENet 1.3.17 (2^20 fragments of a 1-byte message) is refused", "[net][udp]") {
    std::vector<uint8_t> bomb = to_peer();
    add_fragment(bomb, 0x88, 2, 1, 1u << 20, 0, 1);
    CHECK(judge_peer_commands(bomb, true) == peer_commands_verdict::fragment_oversize);
    CHECK(judge_peer_commands(bomb, false) == peer_commands_verdict::before_hello);
    // The same claim on the unreliable fragment command.
    std::vector<uint8_t> unreliable = to_peer();
    add_fragment(unreliable, 0x0C, 2, 1, 1u << 20, 0, 1);
    CHECK(judge_peer_commands(unreliable, true) == peer_commands_verdict::fragment_oversize);
    // Hidden behind an honest command in the same datagram.
    std::vector<uint8_t> behind = to_peer();
    add_ping(behind, 7);
    add_reliable(behind, 2, 10);
    add_fragment(behind, 0x88, 3, 1, 1u << 20, 0, 1);
    CHECK(judge_peer_commands(behind, true) == peer_commands_verdict::fragment_oversize);
}

TEST_CASE("fragments as ENet cuts a message pass after Hello, up to the largest client frame", "[net][udp]") {
    // 3000 bytes at 1364 a fragment: three, the last one 272 bytes.
    for (uint32_t number = 0; number < 3; ++number) {
        std::vector<uint8_t> d = to_peer();
        add_fragment(d, 0x88, 5, number < 2 ? 1364 : 272, 3, number, 3000);
        CHECK(judge_peer_commands(d, true) == peer_commands_verdict::pass);
    }
    // One fragment more than the length needs.
    std::vector<uint8_t> greedy = to_peer();
    add_fragment(greedy, 0x88, 5, 1364, 4, 0, 3000);
    CHECK(judge_peer_commands(greedy, true) == peer_commands_verdict::fragment_oversize);
    // The largest client frame (prefix and 64 KiB) in fragments; one byte more is refused.
    const uint32_t largest = peer_command_limits{}.max_message;
    std::vector<uint8_t> whole = to_peer();
    add_fragment(whole, 0x88, 5, 1000, (largest + 999) / 1000, 0, largest);
    CHECK(judge_peer_commands(whole, true) == peer_commands_verdict::pass);
    std::vector<uint8_t> over = to_peer();
    add_fragment(over, 0x88, 5, 1000, (largest + 1000) / 1000, 0, largest + 1);
    CHECK(judge_peer_commands(over, true) == peer_commands_verdict::fragment_oversize);
    // A fragment of no bytes.
    std::vector<uint8_t> empty = to_peer();
    add_fragment(empty, 0x88, 5, 0, 1, 0, 10);
    CHECK(judge_peer_commands(empty, true) == peer_commands_verdict::fragment_oversize);
}

TEST_CASE("before Hello a peer may send its Hello and ENet's own commands, nothing ENet would hold", "[net][udp]") {
    // The Hello (reliable, sequence 1), resent, and pings on the control channel.
    std::vector<uint8_t> hello = to_peer();
    add_ping(hello, 9);
    add_reliable(hello, 1, 120);
    CHECK(judge_peer_commands(hello, false) == peer_commands_verdict::pass);
    // A reliable command far ahead of the Hello waits in ENet's queue: refused before Hello.
    std::vector<uint8_t> ahead = to_peer();
    add_reliable(ahead, 5, 10);
    CHECK(judge_peer_commands(ahead, false) == peer_commands_verdict::before_hello);
    CHECK(judge_peer_commands(ahead, true) == peer_commands_verdict::pass);
    // An unreliable command may wait for a reliable one: refused before Hello.
    std::vector<uint8_t> unreliable = to_peer();
    unreliable.insert(unreliable.end(), {0x07, 0x01, 0x00, 0x09, 0x00, 0x01, 0x00, 0x02, 0x43, 0x44});
    CHECK(judge_peer_commands(unreliable, false) == peer_commands_verdict::before_hello);
    CHECK(judge_peer_commands(unreliable, true) == peer_commands_verdict::pass);
    // An unsequenced command is delivered at once (the match refuses anything but a Hello).
    std::vector<uint8_t> unsequenced = to_peer();
    unsequenced.insert(unsequenced.end(), {0x49, 0x01, 0x00, 0x00, 0x00, 0x01, 0x00, 0x02, 0x43, 0x44});
    CHECK(judge_peer_commands(unsequenced, false) == peer_commands_verdict::pass);
    // A reliable fragment, however honest, before Hello: a Hello fits one datagram.
    std::vector<uint8_t> fragment = to_peer();
    add_fragment(fragment, 0x88, 1, 1364, 3, 0, 3000);
    CHECK(judge_peer_commands(fragment, false) == peer_commands_verdict::before_hello);
}

TEST_CASE("the commands are read as ENet reads them: it stops where one does not fit", "[net][udp]") {
    // A send command whose data runs past the datagram ends the walk: ENet ignores the rest too.
    std::vector<uint8_t> cut = to_peer();
    cut.insert(cut.end(), {0x86, 0x00, 0x00, 0x01, 0xFF, 0xFF, 0x41});
    add_fragment(cut, 0x88, 2, 1, 1u << 20, 0, 1);  // inside the claimed data: ENet never reads it as a command
    CHECK(judge_peer_commands(cut, true) == peer_commands_verdict::pass);
    // An unknown command number ends it as well.
    std::vector<uint8_t> unknown = to_peer();
    unknown.insert(unknown.end(), {0x0E, 0x00, 0x00, 0x01});
    add_fragment(unknown, 0x88, 2, 1, 1u << 20, 0, 1);
    CHECK(judge_peer_commands(unknown, true) == peer_commands_verdict::pass);
    // A fragment header cut short is never read past the datagram's end.
    std::vector<uint8_t> short_fragment = to_peer();
    add_fragment(short_fragment, 0x88, 2, 1, 1u << 20, 0, 1);
    short_fragment.resize(short_fragment.size() - 10);
    CHECK(judge_peer_commands(short_fragment, true) == peer_commands_verdict::pass);
    // Too short for a header, or compressed (our host has no compressor): ENet drops them.
    CHECK(judge_peer_commands(std::vector<uint8_t>{0x10}, false) == peer_commands_verdict::pass);
    std::vector<uint8_t> compressed = to_peer();
    compressed[0] |= 0x40;
    add_fragment(compressed, 0x88, 2, 1, 1u << 20, 0, 1);
    CHECK(judge_peer_commands(compressed, true) == peer_commands_verdict::pass);
}

TEST_CASE("the gate counts peer datagrams refused before Hello and for their fragments", "[net][udp]") {
    connect_gate gate;
    std::vector<uint8_t> bomb = to_peer();
    add_fragment(bomb, 0x88, 2, 1, 1u << 20, 0, 1);
    CHECK(gate.judge(bomb, "10.0.0.1", 0) == gate_verdict::pass);  // to a peer slot: judged by its commands
    CHECK(gate.judge_peer(bomb, false) == gate_verdict::refuse_before_hello);
    CHECK(gate.judge_peer(bomb, true) == gate_verdict::refuse_fragment);
    std::vector<uint8_t> hello = to_peer();
    add_reliable(hello, 1, 100);
    CHECK(gate.judge_peer(hello, false) == gate_verdict::pass);
    CHECK(gate.refused_before_hello() == 1);
    CHECK(gate.refused_fragment() == 1);
}
