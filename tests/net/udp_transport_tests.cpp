// arena-server's UDP transport (--udp-port, ENet) end to end over loopback: joining, inputs
// and snapshots, the same admission as TCP, and hostile datagrams.
#include <signal.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <thread>

#include "protocol/decode.hpp"
#include "protocol/version.hpp"
#include "server/auth/join_token.hpp"
#include "server_process.hpp"
#include "udp_client.hpp"
#include "udp_raw_enet.hpp"

using namespace arena;
using namespace arena::test;
using namespace std::chrono_literals;
using protocol::Payload;

namespace {

// Hello on the reliable channel, then the Welcome.
void join(udp_client& c, const std::string& name = "udp-tester") {
    REQUIRE(c.connected());
    c.send_reliable(protocol::encode_hello(protocol::protocol_version, name, ""));
    auto welcome = c.read_until(Payload::Welcome, 3000ms);
    REQUIRE(welcome);
    REQUIRE(protocol::decode_welcome(*message_of(*welcome)));
}

protocol::reject_msg expect_reject(udp_client& c) {
    auto frame = c.read_until(Payload::Reject, 4000ms);
    REQUIRE(frame);
    auto r = protocol::decode_reject(*message_of(*frame));
    REQUIRE(r);
    return r.value;
}

struct play_figures {
    int snapshots = 0;
    uint32_t max_ack = 0;
    uint32_t sent = 0;
};

// Sends one input per tick (60 Hz) unreliably and counts the snapshots and their acks.
play_figures play(udp_client& c, std::chrono::milliseconds duration, uint32_t first_sequence = 1,
                  const std::function<void()>& between = {}) {
    play_figures f;
    const auto start = std::chrono::steady_clock::now();
    uint32_t sequence = first_sequence;
    while (std::chrono::steady_clock::now() - start < duration) {
        c.send_unreliable(protocol::encode_input({sequence++, 1.0f, 0.0f, 0}));
        ++f.sent;
        if (between) between();
        const auto next = start + f.sent * 16667us;
        while (std::chrono::steady_clock::now() < next) {
            auto frame = c.read_frame(2ms);
            if (!frame) continue;
            const protocol::Message* m = message_of(*frame);
            if (m == nullptr || m->payload_type() != Payload::Snapshot) continue;
            auto s = protocol::decode_snapshot(*m);
            REQUIRE(s);
            ++f.snapshots;
            f.max_ack = std::max(f.max_ack, s.value.ack_sequence);
        }
    }
    return f;
}

}  // namespace

TEST_CASE("a client joins over UDP beside TCP, its inputs are consumed and snapshots arrive", "[net][udp]") {
    udp_server server({"--preset", "asteroids"});
    CHECK(server.udp_port != server.process.port());
    udp_client c(server.udp_port);
    join(c);
    const play_figures f = play(c, 1500ms);
    // 20 snapshots a second for 1.5 s over loopback: allow for the start and a loaded machine.
    CHECK(f.snapshots >= 20);
    // The world consumed the inputs: the ack follows the newest sequence sent, a few ticks behind.
    CHECK(f.max_ack + 20 >= f.sent);
    CHECK(f.max_ack > 0);
    CHECK(server.process.log_shows("udp: ENet on"));
    CHECK(server.process.stop(SIGTERM) == 0);
}

TEST_CASE("a spectator over UDP sees a TCP player's ship and its Input is refused", "[net][udp][spectator]") {
    udp_server server({"--preset", "asteroids"});
    test_client player(server.process.port());
    player.send_frame(protocol::encode_hello(protocol::protocol_version, "player", ""));
    auto frame = player.read_until(Payload::Welcome);
    REQUIRE(frame);
    auto player_welcome = protocol::decode_welcome(*message_of(*frame));
    REQUIRE(player_welcome);

    udp_client eye(server.udp_port);
    REQUIRE(eye.connected());
    eye.send_reliable(protocol::encode_hello(protocol::protocol_version, "eye", "", true, true));
    frame = eye.read_until(Payload::Welcome, 3000ms);
    REQUIRE(frame);
    auto welcome = protocol::decode_welcome(*message_of(*frame));
    REQUIRE(welcome);
    CHECK(welcome.value.entity_id == 0);
    CHECK(welcome.value.view_radius == 0.0f);
    bool seen = false;
    for (int i = 0; i < 40 && !seen; ++i) {
        frame = eye.read_until(Payload::Snapshot, 3000ms);
        REQUIRE(frame);
        auto snapshot = protocol::decode_snapshot(*message_of(*frame));
        REQUIRE(snapshot);
        CHECK_FALSE(snapshot.value.is_delta);  // a spectator acknowledges nothing: full snapshots
        for (const protocol::BodyState& b : snapshot.value.bodies)
            seen = seen || b.owner() == player_welcome.value.player_id;
    }
    CHECK(seen);
    eye.send_unreliable(protocol::encode_input({1, 1.0f, 0.0f, 0}));
    CHECK(expect_reject(eye).code == protocol::RejectCode::bad_request);
    CHECK(server.process.stop(SIGTERM) == 0);
}

TEST_CASE("UDP peers count as connections like TCP ones: the stats line's connections=", "[net][udp]") {
    udp_server server({"--stats-interval", "0.2"});
    test_client tcp(server.process.port());
    udp_client c(server.udp_port);
    join(c);
    // A stats line after `from` in the log showing `text`, within 3 s.
    auto stats_line_after = [&](size_t from, const std::string& text) {
        for (int k = 0; k < 60; ++k) {
            if (server.process.log().find(text, from) != std::string::npos) return true;
            std::this_thread::sleep_for(50ms);
        }
        return false;
    };
    CHECK(stats_line_after(0, "connections=2\n"));
    // A Bye: the server closes the peer once ENet delivered its last word, and forgets it.
    c.send_reliable(protocol::encode_bye("done"));
    c.pump(500ms);
    CHECK(stats_line_after(server.process.log().size(), "connections=1\n"));
    CHECK(server.process.stop(SIGTERM) == 0);
}

// Snapshot ticks received in `duration` while sending an input per tick, and how often each.
std::map<uint32_t, int> snapshot_ticks(udp_client& c, std::chrono::milliseconds duration) {
    std::map<uint32_t, int> seen;
    // Warm up: the first snapshots may come before the copies start. The sequences then go on
    // without a gap, as an honest client's do (a gap is a lost input, which the copies heed).
    const play_figures warm_up = play(c, duration, 1, {});
    const auto start = std::chrono::steady_clock::now();
    uint32_t sequence = 1 + warm_up.sent;
    while (std::chrono::steady_clock::now() - start < duration) {
        c.send_unreliable(protocol::encode_input({sequence++, 0.0f, 0.0f, 0}));
        const auto next = std::chrono::steady_clock::now() + 16667us;
        while (std::chrono::steady_clock::now() < next) {
            auto frame = c.read_frame(2ms);
            if (!frame) continue;
            const protocol::Message* m = message_of(*frame);
            if (m == nullptr || m->payload_type() != Payload::Snapshot) continue;
            auto s = protocol::decode_snapshot(*m);
            REQUIRE(s);
            ++seen[s.value.tick];
        }
    }
    return seen;
}

TEST_CASE("each UDP snapshot goes twice with --udp-snapshot-copies 2, once by default and with auto on loopback",
          "[net][udp]") {
    // 0: auto; this client acknowledges no snapshot (and loopback loses none): once.
    const int setting = GENERATE(1, 2, 0);
    const int copies = setting == 2 ? 2 : 1;
    udp_server server(setting == 2   ? std::vector<std::string>{"--udp-snapshot-copies", "2"}
                      : setting == 0 ? std::vector<std::string>{"--udp-snapshot-copies", "auto"}
                                     : std::vector<std::string>{});
    udp_client c(server.udp_port);
    join(c);
    const std::map<uint32_t, int> seen = snapshot_ticks(c, 1000ms);
    REQUIRE(seen.size() >= 10);
    int twice = 0;
    for (const auto& [tick, n] : seen) {
        CHECK(n <= copies);
        twice += n == 2 ? 1 : 0;
    }
    // Loopback loses nothing: every snapshot came `copies` times, but perhaps the first (its
    // other copy read while warming up) and the last (its copy still to come).
    if (copies == 2) CHECK(twice + 2 >= static_cast<int>(seen.size()));
    if (copies == 1) CHECK(twice == 0);
    CHECK(server.process.stop(SIGTERM) == 0);
}

TEST_CASE("a UDP datagram whose length prefix is too large is refused like those bytes on TCP", "[net][udp]") {
    udp_server server({});
    udp_client c(server.udp_port);
    REQUIRE(c.connected());
    const std::vector<uint8_t> garbage = {'h', 'e', 'l', 'l', 'o', ' ', 'w', 'o', 'r', 'l', 'd'};
    c.send_reliable(garbage);
    CHECK(expect_reject(c).code == protocol::RejectCode::too_large);
    c.pump(500ms);
    CHECK(c.disconnected());
}

TEST_CASE("a UDP datagram holding a frame and more is refused: one datagram, one frame", "[net][udp]") {
    udp_server server({});
    udp_client c(server.udp_port);
    REQUIRE(c.connected());
    protocol::frame_bytes frame = protocol::encode_hello(protocol::protocol_version, "two", "");
    frame.push_back(0);
    c.send_reliable(frame);
    const protocol::reject_msg r = expect_reject(c);
    CHECK(r.code == protocol::RejectCode::bad_request);
    CHECK(r.reason.find("not exactly one frame") != std::string::npos);
    c.pump(500ms);
    CHECK(c.disconnected());
}

TEST_CASE("a UDP Hello with the wrong protocol version gets the same Reject as on TCP", "[net][udp]") {
    udp_server server({});
    udp_client c(server.udp_port);
    REQUIRE(c.connected());
    c.send_reliable(protocol::encode_hello(protocol::protocol_version + 1, "old", ""));
    CHECK(expect_reject(c).code == protocol::RejectCode::version_mismatch);
}

TEST_CASE("a UDP peer that connects and never says Hello is dropped after the handshake timeout", "[net][udp]") {
    udp_server server({"--handshake-timeout", "1"});
    udp_client c(server.udp_port);
    REQUIRE(c.connected());
    CHECK(expect_reject(c).code == protocol::RejectCode::timeout);
    c.pump(1000ms);
    CHECK(c.disconnected());
}

TEST_CASE("a UDP Hello joins though the acknowledgement of VERIFY_CONNECT before it was lost", "[net][udp]") {
    udp_server server({});
    raw_udp_socket client(server.udp_port);
    client.send(enet_connect_datagram(0x2A2A2A2A));
    // The server's VERIFY_CONNECT brings the peer id and the session to send with.
    std::optional<std::vector<uint8_t>> verify;
    while (!verify) {
        auto datagram = client.receive(2000ms);
        REQUIRE(datagram);
        const size_t header = ((*datagram)[0] & 0x80) ? 4 : 2;
        if (datagram->size() >= header + 44 && ((*datagram)[header] & 0x0F) == 3) verify = datagram;
    }
    const size_t at = ((*verify)[0] & 0x80) ? 4 : 2;
    const auto peer_id = static_cast<uint16_t>(((*verify)[at + 4] << 8) | (*verify)[at + 5]);
    const uint8_t session = (*verify)[at + 7];  // its outgoingSessionID: the session a client sends with
    // The acknowledgement is lost; the Hello, sent in a datagram of its own as an ENet client
    // does, arrives. ENet alone drops it unacknowledged until the acknowledgement comes, and
    // this client never sends either again.
    const auto hello = protocol::encode_hello(protocol::protocol_version, "unacknowledged", "");
    auto hello_datagram = [&](uint8_t with_session) {
        std::vector<uint8_t> d = {static_cast<uint8_t>(0x80 | (with_session << 4) | (peer_id >> 8)),
                                  static_cast<uint8_t>(peer_id & 0xFF),
                                  0x00,
                                  0x00,
                                  0x86,  // SEND_RELIABLE | ACKNOWLEDGE
                                  0x00,  // channel 0
                                  0x00,
                                  0x01,  // sequence 1
                                  static_cast<uint8_t>(hello.size() >> 8),
                                  static_cast<uint8_t>(hello.size() & 0xFF)};
        d.insert(d.end(), hello.begin(), hello.end());
        return d;
    };
    // Neither another session nor another port proves anything.
    client.send(hello_datagram(session ^ 1));
    send_raw_datagram(server.udp_port, hello_datagram(session));
    CHECK_FALSE(server.process.log_shows("hello player=1", 500ms));
    client.send(hello_datagram(session));
    CHECK(server.process.log_shows("hello player=1 name=unacknowledged", 2000ms));
}

TEST_CASE("random datagrams, truncated ENet headers and a connect flood leave an honest UDP client its snapshots",
          "[net][udp][hostile]") {
    const std::string stats_path = temp_path("udp-flood-stats.json");
    udp_server server({"--preset", "asteroids", "--stats-json", stats_path});
    udp_client honest(server.udp_port);
    join(honest);
    const play_figures calm = play(honest, 1000ms);
    REQUIRE(calm.snapshots >= 12);

    std::mt19937 rng(7);
    std::vector<std::unique_ptr<ENetHost, void (*)(ENetHost*)>> flood;
    ENetAddress to{};
    enet_address_set_host_ip(&to, "127.0.0.1");
    to.port = server.udp_port;
    int round = 0;
    // Each tick: 20 random datagrams, 20 truncated headers, and 2 ENet connects from new ports.
    auto attack = [&] {
        for (int i = 0; i < 20; ++i) {
            std::vector<uint8_t> bytes(rng() % 1400);
            for (auto& b : bytes) b = static_cast<uint8_t>(rng());
            send_raw_datagram(server.udp_port, bytes);
            std::vector<uint8_t> header(1 + rng() % 7);
            for (auto& b : header) b = static_cast<uint8_t>(rng());
            header[0] = 0x8F;  // a connect's peer id 0xFFF with the sent-time flag
            if (header.size() > 1) header[1] = 0xFF;
            send_raw_datagram(server.udp_port, header);
        }
        for (int i = 0; i < 2; ++i) {
            ENetHost* h = enet_host_create(nullptr, 1, 2, 0, 0);
            if (h == nullptr) continue;
            enet_host_connect(h, &to, 2, 0);
            enet_host_flush(h);
            flood.emplace_back(h, &enet_host_destroy);
        }
        ++round;
    };
    const play_figures stormy = play(honest, 2000ms, calm.sent + 1, attack);
    // The honest client keeps its snapshot rate (20 a second; allow a loaded machine a quarter)
    // and its inputs keep being consumed.
    CHECK(stormy.snapshots >= 30);
    CHECK(stormy.max_ack + 30 >= calm.sent + stormy.sent);

    // The flood's connects were gated per address: of ~240 only the burst and the refill got
    // a peer slot (16 + 4 a second over ~2 s, with slack for timing).
    int connected = 0;
    for (auto& h : flood) {
        ENetEvent event{};
        while (enet_host_service(h.get(), &event, 0) > 0)
            if (event.type == ENET_EVENT_TYPE_CONNECT) ++connected;
    }
    INFO("flood hosts " << flood.size() << ", connected " << connected << ", rounds " << round);
    CHECK(flood.size() >= 100);
    CHECK(connected >= 1);
    CHECK(connected <= 40);
    // The refusals were logged, one line per reason at first, and counted by reason.
    CHECK(server.process.log_shows("udp: refused a datagram from 127.0.0.1: over its address's connect rate"));
    CHECK(server.process.log_shows("udp: refused a datagram from 127.0.0.1: not an ENet connect"));
    CHECK(server.process.stop(SIGTERM) == 0);
    const std::string stats = read_file(stats_path);
    CHECK(stats.find("\"udp_refused\": {") != std::string::npos);
    CHECK(stats.find("\"rate\": ") != std::string::npos);
    CHECK(stats.find("\"shape\": ") != std::string::npos);
    std::remove(stats_path.c_str());
}

TEST_CASE("a UDP connect with every peer slot taken is refused, logged and counted", "[net][udp]") {
    const std::string stats_path = temp_path("udp-peer-limit-stats.json");
    // --max-connections 1: ENet gets one peer slot.
    udp_server server({"--max-connections", "1", "--stats-json", stats_path});
    udp_client first(server.udp_port);
    join(first, "first");
    udp_client second(server.udp_port, 1500ms);
    CHECK_FALSE(second.connected());
    CHECK(server.process.log_shows("udp: refused a datagram from 127.0.0.1: every peer slot is taken"));
    CHECK(server.process.stop(SIGTERM) == 0);
    const std::string stats = read_file(stats_path);
    CHECK(stats.find("\"peer_limit\": ") != std::string::npos);
    std::remove(stats_path.c_str());
}

TEST_CASE("with --token-secret a UDP connect without the server's connect key gets no peer slot", "[net][udp][auth]") {
    const std::string stats_path = temp_path("udp-connect-key-stats.json");
    const std::string secret_path = temp_path("udp-connect-key-secret");
    const std::string secret_bytes = "0123456789abcdef0123456789abcdef-udp-key-test";
    std::ofstream(secret_path) << secret_bytes;
    // One ENet peer slot: a connect that got past the gate would hold it.
    udp_server server({"--token-secret", secret_path, "--max-connections", "1", "--stats-json", stats_path});
    const auto secret = auth::token_secret::from_bytes(secret_bytes).value;
    const uint32_t key = secret.connect_key(auth::unix_now());

    udp_client keyless(server.udp_port, 1000ms);  // ENet's default connect data, 0
    CHECK_FALSE(keyless.connected());
    udp_client wrong_key(server.udp_port, 1000ms, key ^ 0x00010000);
    CHECK_FALSE(wrong_key.connected());
    CHECK(server.process.log_shows(
        "udp: refused a datagram from 127.0.0.1: a connect without this server's connect key"));

    // Both are still trying, yet the one slot is free: the client with the key joins with its token.
    udp_client honest(server.udp_port, 2000ms, key);
    REQUIRE(honest.connected());
    honest.send_reliable(protocol::encode_hello(protocol::protocol_version, "claims-to-be-bob",
                                                secret.mint("alice", auth::unix_now() + 60)));
    REQUIRE(honest.read_until(Payload::Welcome, 3000ms));
    CHECK(server.process.log_shows("name=alice"));

    CHECK(server.process.stop(SIGTERM) == 0);
    const std::string stats = read_file(stats_path);
    CHECK(stats.find("\"connect_key\": ") != std::string::npos);
    CHECK(stats.find("\"peer_limit\": ") == std::string::npos);  // the keyless never reached the slots
    std::remove(stats_path.c_str());
    std::remove(secret_path.c_str());
}
