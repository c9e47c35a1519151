// The frames a session sends, byte for byte: a scripted Asteroids match of delta clients (some
// within a datagram's budget), BodyState clients and a spectator, every frame each one is sent
// hashed in order. Work on the fan-out that is meant to make it cheaper (when a client's
// snapshot is built, how a view is found, how a delta is encoded) must leave every byte as it
// was: the hash below is the one the fan-out gave before that work. A change that means to
// change the bytes says why and updates it.
#include <catch2/catch.hpp>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "match/drive.hpp"
#include "server/world/fnv1a.hpp"
#include "server/world/presets.hpp"
#include "server/world/splitmix64.hpp"

using namespace arena;
using namespace arena::match_test;

namespace {

struct hashing_client : match::connection {
    explicit hashing_client(size_t budget) : budget(budget) {}
    size_t budget;
    world::fnv1a_64 hash;
    uint64_t frames = 0;
    std::deque<std::pair<uint32_t, uint32_t>> arrived;  // (arrival tick, snapshot tick)
    uint32_t acked = 0;
    uint32_t now = 0;

    void keep(std::span<const uint8_t> frame) {
        hash.add_u32(static_cast<uint32_t>(frame.size()));
        hash.add_bytes(frame);
        ++frames;
    }
    void send(protocol::frame_bytes frame) override { keep(frame); }
    void send_snapshot(const protocol::snapshot_encoder& s, uint32_t ack) override { snapshot(s.frame_with_ack(ack)); }
    void send_snapshot_frame(std::span<const uint8_t> frame) override { snapshot(frame); }
    void snapshot(std::span<const uint8_t> frame) {
        keep(frame);
        protocol::frame_bytes storage;
        arrived.push_back({now, read_snapshot(frame, storage).tick});
    }
    void close(protocol::RejectCode, std::string_view why) override { FAIL("a scripted client was closed: " << why); }
    void close_with_bye(std::string_view) override {}
    size_t snapshot_budget() const override { return budget; }
    std::string_view peer() const override { return "golden"; }

    // What it acknowledges at tick t: the newest snapshot that arrived 6 ticks (100 ms) ago.
    uint32_t ack_at(uint32_t t) {
        while (!arrived.empty() && arrived.front().first + 6 <= t) {
            acked = arrived.front().second;
            arrived.pop_front();
        }
        return acked;
    }
};

struct session_hash {
    uint64_t hash = 0;
    uint64_t frames = 0;
};

session_hash run_session() {
    world::world_config w = world::asteroids_preset();
    w.rules = "asteroids";
    match::match_config config;
    config.seed = 7;
    config.tick_rate = 60;
    config.snapshot_rate = 20;
    config.view_radius = 60.0f;
    match::match m(config, w);

    // 40 delta clients over a stream, 8 within a 600-byte datagram, 4 BodyState clients, a
    // spectator; they join over the first second.
    std::vector<std::unique_ptr<hashing_client>> clients;
    std::vector<protocol::hello_msg> hellos;
    for (int i = 0; i < 53; ++i) {
        const bool budgeted = i % 6 == 5 && i < 48;
        clients.push_back(std::make_unique<hashing_client>(budgeted ? 600 : 0));
        std::string name = "p";
        name += std::to_string(i);
        protocol::hello_msg hello{protocol::protocol_version, name, "", i < 48};
        hello.spectator = i == 52;
        hellos.push_back(hello);
    }
    world::splitmix64 rng(11);
    std::vector<uint32_t> sequence(clients.size(), 0);
    for (uint32_t t = 0; t < 900; ++t) {
        for (size_t i = 0; i < clients.size(); ++i) {
            hashing_client& c = *clients[i];
            c.now = t;
            if (t == i) REQUIRE(join(m, c, hellos[i], hellos[i].name) != 0);
            if (t <= i) continue;
            if (hellos[i].spectator) {
                if (t % 60 == 0) REQUIRE(deliver(m, c, protocol::encode_ping(t)));  // a spectator's sign of life
                continue;
            }
            protocol::input_msg in{++sequence[i], 0.0f, 0.0f, 0, c.ack_at(t)};
            const uint64_t r = rng.next();
            in.thrust = static_cast<float>(r % 5) * 0.25f - 0.25f;
            in.turn = static_cast<float>((r >> 8) % 5) * 0.5f - 1.0f;
            in.buttons = (r >> 16) % 4 == 0 ? 1 : 0;
            REQUIRE(send_input(m, c, in));
        }
        m.tick();
    }
    session_hash out;
    world::fnv1a_64 all;
    for (const auto& c : clients) {
        all.add_u64(c->hash.value());
        out.frames += c->frames;
    }
    out.hash = all.value();
    return out;
}

}  // namespace

TEST_CASE("every frame of a scripted session is the bytes the fan-out sent before", "[match][delta][golden]") {
    const session_hash got = run_session();
    INFO("frames " << got.frames << ", hash 0x" << std::hex << got.hash);
    CHECK(got.frames > 53 * 250);  // every client got its snapshots
    // Delta clients take their snapshots in groups of 16 player ids (match.hpp snapshot_group),
    // so players 1 to 16 now share a tick and these frames' ticks and baselines moved. Then
    // every Welcome's world_version went from 3 to 4 (the sub-stepped solver; this world is
    // not sub-stepped, so its snapshots are the bytes they were).
    CHECK(got.hash == 0xa83c20b0f19384c2ULL);
}
