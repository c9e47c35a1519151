// Hostile ENet peers of arena-server's UDP transport, over loopback: what a peer can make the
// server hold before it says Hello (fragment bombs, half-open handshakes) and what a connect
// that is never answered gets back (amplification).
#include <signal.h>

#include <catch2/catch.hpp>
#include <memory>
#include <string>
#include <thread>

#include "protocol/decode.hpp"
#include "protocol/version.hpp"
#include "server_process.hpp"
#include "udp_client.hpp"
#include "udp_raw_enet.hpp"

using namespace arena;
using namespace arena::test;
using namespace std::chrono_literals;
using protocol::Payload;

namespace {

bool joins(udp_client& c, const std::string& name) {
    if (!c.connected()) return false;
    c.send_reliable(protocol::encode_hello(protocol::protocol_version, name, ""));
    return c.read_until(Payload::Welcome, 3000ms).has_value();
}

// The bomb of the finding: fragment starts claiming 2^20 fragments of a 1-byte message (ENet
// 1.3.17 allocated a 128 KiB bitmap for each), 150 to a datagram.
void send_fragment_bomb(raw_udp_socket& socket, raw_enet_peer peer, uint16_t first_sequence, int starts) {
    for (int sent = 0; sent < starts; sent += 150)
        socket.send(enet_fragment_starts(peer, static_cast<uint16_t>(first_sequence + sent), 150, 1u << 20, 1));
}

}  // namespace

TEST_CASE("fragment starts claiming 2^20 fragments from a peer, before and after its Hello, cost no memory",
          "[net][udp][hostile]") {
    const std::string stats_path = temp_path("udp-fragment-bomb-stats.json");
    udp_server server({"--stats-json", stats_path});
    raw_udp_socket attacker(server.udp_port);
    const auto peer = raw_enet_handshake(attacker, 0x0B0B0B0B);
    REQUIRE(peer);
    std::this_thread::sleep_for(200ms);  // the server counts the peer connected
    const long before_kib = server.process.rss_kib();

    // 1050 starts: 130 MiB of bitmaps without the gate. Before Hello no fragment is admitted.
    send_fragment_bomb(attacker, *peer, 2, 1050);
    CHECK(server.process.log_shows(
        "udp: refused a datagram from 127.0.0.1: a fragment or a queued command before Hello", 3000ms));
    const long after_bomb_kib = server.process.rss_kib();
    INFO("RSS before " << before_kib << " KiB, after the bomb before Hello " << after_bomb_kib << " KiB");
    CHECK(after_bomb_kib - before_kib < 16 * 1024);

    // After its Hello the peer may send fragments, but no more of them than their length allows.
    attacker.send(enet_reliable_datagram(*peer, 1, protocol::encode_hello(protocol::protocol_version, "bomber", "")));
    REQUIRE(server.process.log_shows("hello player=1 name=bomber", 3000ms));
    send_fragment_bomb(attacker, *peer, 1100, 1050);  // new sequence numbers: new messages
    CHECK(server.process.log_shows("udp: refused a datagram from 127.0.0.1: fragments their length does not need",
                                   3000ms));
    const long after_kib = server.process.rss_kib();
    INFO("after the bomb after Hello " << after_kib << " KiB");
    CHECK(after_kib - before_kib < 16 * 1024);

    CHECK(server.process.stop(SIGTERM) == 0);
    const std::string stats = read_file(stats_path);
    CHECK(stats.find("\"before_hello\": ") != std::string::npos);
    CHECK(stats.find("\"fragment\": ") != std::string::npos);
    std::remove(stats_path.c_str());
}

TEST_CASE("a message fragmented by ENet from a joined peer still arrives", "[net][udp]") {
    udp_server server({});
    udp_client c(server.udp_port);
    REQUIRE(joins(c, "fragmenter"));
    // 3000 bytes: three fragments at ENet's MTU. A frame whose body is no FlatBuffer: the
    // Reject proves the whole message reached the match.
    std::vector<uint8_t> frame(3000, 0);
    frame[0] = static_cast<uint8_t>((3000 - 4) & 0xFF);
    frame[1] = static_cast<uint8_t>((3000 - 4) >> 8);
    c.send_reliable(frame);
    auto reject = c.read_until(Payload::Reject, 3000ms);
    REQUIRE(reject);
    auto r = protocol::decode_reject(*message_of(*reject));
    REQUIRE(r);
    CHECK(r.value.code == protocol::RejectCode::bad_request);
}

TEST_CASE("half-open handshakes from ten addresses keep no honest UDP client out", "[net][udp][hostile]") {
    const std::string stats_path = temp_path("udp-half-open-stats.json");
    // 40 peer slots. Without a bound, the ten addresses' connect bursts (16 each) take them all
    // and hold them for ENet's 30 s.
    udp_server server({"--max-connections", "40", "--stats-json", stats_path});
    std::vector<std::unique_ptr<raw_udp_socket>> attackers;
    for (int host = 2; host <= 11; ++host)
        attackers.push_back(
            std::make_unique<raw_udp_socket>(server.udp_port, ("127.0.0." + std::to_string(host)).c_str()));
    uint32_t connect_id = 1;
    auto attack = [&](int per_address) {
        for (auto& a : attackers)
            for (int i = 0; i < per_address; ++i) a->send(enet_connect_datagram(connect_id++));
    };
    attack(16);
    std::this_thread::sleep_for(100ms);
    int joined = 0;
    std::vector<std::unique_ptr<udp_client>> honest;
    for (int i = 0; i < 8; ++i) {
        attack(4);  // a new connect from every address (the rate's refill allows about this much)
        honest.push_back(std::make_unique<udp_client>(server.udp_port, 3000ms));
        joined += joins(*honest.back(), "honest-" + std::to_string(i)) ? 1 : 0;
    }
    CHECK(joined == 8);
    CHECK(server.process.log_shows("udp: refused a datagram from 127.0.0.", 100ms));
    CHECK(server.process.stop(SIGTERM) == 0);
    const std::string stats = read_file(stats_path);
    CHECK(stats.find("\"half_open\": ") != std::string::npos);
    std::remove(stats_path.c_str());
}

TEST_CASE("sixteen UDP clients behind one address connecting at once are all answered", "[net][udp]") {
    // Players behind one NAT: their handshakes are half-open together for a round trip. While
    // there is room, none is refused (a limit of two half-open per address answered two).
    udp_server server({"--max-connections", "40"});
    std::vector<std::unique_ptr<raw_udp_socket>> players;
    for (int i = 0; i < 16; ++i) players.push_back(std::make_unique<raw_udp_socket>(server.udp_port));
    uint32_t connect_id = 0x1000;
    for (auto& p : players) p->send(enet_connect_datagram(connect_id++));
    int answered = 0;
    for (auto& p : players) answered += p->receive(1000ms).has_value() ? 1 : 0;
    CHECK(answered == 16);
    CHECK(server.process.stop(SIGTERM) == 0);
}

TEST_CASE("with every UDP slot half-open, a connect from another address takes the oldest one's slot at once",
          "[net][udp][hostile]") {
    udp_server server({"--max-connections", "4"});
    raw_udp_socket spoofer_a(server.udp_port, "127.0.0.2");
    raw_udp_socket spoofer_b(server.udp_port, "127.0.0.3");
    for (uint32_t id = 1; id <= 4; ++id) spoofer_a.send(enet_connect_datagram(id));
    std::this_thread::sleep_for(100ms);
    // Full: a fifth from the same address is refused; one from an address holding fewer gets in.
    spoofer_a.send(enet_connect_datagram(5));
    spoofer_b.send(enet_connect_datagram(6));
    CHECK(spoofer_b.receive(500ms).has_value());
    // Well before the 1 s reset: the honest client takes another spoofed slot the same way.
    udp_client honest(server.udp_port, 500ms);
    CHECK(joins(honest, "beside-the-spoof"));
    CHECK(server.process.log_shows("udp: refused a datagram from 127.0.0.2: no slot free", 500ms));
    CHECK(server.process.stop(SIGTERM) == 0);
}

TEST_CASE("a UDP connect never answered gets back no more bytes than it sent, and its slot is freed",
          "[net][udp][hostile]") {
    // One peer slot: the half-open peer holds it until it is reset.
    udp_server server({"--max-connections", "1"});
    raw_udp_socket spoofed(server.udp_port);
    const std::vector<uint8_t> connect = enet_connect_datagram(0x5EED5EED);
    spoofed.send(connect);
    // ENet alone resends VERIFY_CONNECT after 0.5 s, 1.5 s, 3.5 s...: read everything for 3 s.
    size_t bytes_back = 0;
    int datagrams_back = 0;
    const auto until = std::chrono::steady_clock::now() + 3000ms;
    while (std::chrono::steady_clock::now() < until) {
        auto datagram = spoofed.receive(100ms);
        if (!datagram) continue;
        bytes_back += datagram->size();
        ++datagrams_back;
    }
    INFO(datagrams_back << " datagrams, " << bytes_back << " bytes back for " << connect.size());
    CHECK(datagrams_back >= 1);
    CHECK(bytes_back <= connect.size());
    // The slot the half-open peer took is free again.
    udp_client honest(server.udp_port, 2000ms);
    CHECK(joins(honest, "after-the-spoof"));
    CHECK(server.process.stop(SIGTERM) == 0);
}
