// The client core with no transport at all: frames in, frames out, the time passed in. What
// arena-bots does over TCP and the simulated network does in virtual time rests on these.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "client_sim/client_core.hpp"
#include "protocol/config_hash.hpp"
#include "protocol/decode.hpp"
#include "protocol/snapshot.hpp"
#include "protocol/verify.hpp"
#include "server/config/config_json.hpp"
#include "server/world/presets.hpp"

namespace {

using namespace arena::bots;
namespace protocol = arena::protocol;
namespace world = arena::world;
using protocol::Payload;

constexpr time_ns ms = 1'000'000;

client_params params(std::string name, bool delta = false) {
    client_params p;
    p.index = 1;
    p.name = std::move(name);
    p.delta_snapshots = delta;
    return p;
}

protocol::welcome_info welcome_for(const world::world_config& config) {
    protocol::welcome_info w;
    w.player_id = 3;
    w.entity_id = 7;
    w.tick = 100;
    w.tick_rate = 60;
    w.snapshot_rate = 20;
    w.preset = "asteroids";
    w.world_config = arena::config::config_to_json(config);
    w.world_config_hash = protocol::world_config_hash(w.world_config);
    w.world_version = world::world_version;
    return w;
}

// The core's output as messages: every one must be a whole, valid client frame.
std::vector<Payload> drain(client_core& core, std::vector<protocol::frame_bytes>* frames = nullptr) {
    std::vector<Payload> types;
    protocol::frame_reader reader;  // the server's limits
    std::span<const std::uint8_t> data = core.output();
    while (!data.empty()) {
        data = data.subspan(reader.feed(data));
        REQUIRE(reader.has_frame());
        const auto verified = protocol::verify_message(reader.frame());
        REQUIRE(verified.ok());
        types.push_back(verified.value->payload_type());
        if (frames) frames->emplace_back(reader.frame().begin(), reader.frame().end());
        reader.next();
    }
    REQUIRE(reader.buffered() == 0);
    core.output().clear();
    return types;
}

struct joined_core {
    world::world_config config = *world::preset_by_name("asteroids");
    client_shared shared;
    client_core core{shared, params("p-1")};

    joined_core() {
        core.launch(0);
        core.connected();
        REQUIRE(drain(core) == std::vector{Payload::Hello});
        core.on_frame(protocol::encode_welcome(welcome_for(config)), 10 * ms);
        REQUIRE(core.current() == client_core::phase::playing);
    }
    void snapshot(std::uint32_t tick, std::uint32_t ack, time_ns now) {
        flatbuffers::FlatBufferBuilder fbb;
        const protocol::BodyState own(7, 3, 100, 100, 1, 0, 0, 0);
        const auto frame = protocol::encode_snapshot(fbb, tick, ack, {&own, 1});
        core.on_frame(frame, now);
    }
};

}  // namespace

TEST_CASE("the core says Hello with its name, token and delta flag once connected", "[client_core]") {
    client_shared shared;
    client_params p = params("bot-4", true);
    p.token = "secret";
    client_core core(shared, p);
    core.launch(0);
    CHECK(core.output().empty());  // nothing before the transport is up
    core.connected();
    std::vector<protocol::frame_bytes> frames;
    REQUIRE(drain(core, &frames) == std::vector{Payload::Hello});
    const auto hello = protocol::decode_hello(*protocol::verify_message(frames[0]).value);
    REQUIRE(hello.ok());
    CHECK(hello.value.name == "bot-4");
    CHECK(hello.value.token == "secret");
    CHECK(hello.value.delta_snapshots);
    CHECK(hello.value.protocol_version == protocol::protocol_version);
    CHECK(core.current() == client_core::phase::joining);
}

TEST_CASE("a Welcome split byte by byte joins as one whole does", "[client_core]") {
    const world::world_config config = *world::preset_by_name("platformer");
    const protocol::frame_bytes welcome = protocol::encode_welcome(welcome_for(config));
    client_shared shared;
    client_core core(shared, params("b"));
    core.launch(0);
    core.connected();
    for (std::size_t i = 0; i < welcome.size(); ++i) {
        REQUIRE(core.current() == client_core::phase::joining);
        core.on_bytes({&welcome[i], 1}, 5 * ms);
    }
    CHECK(core.current() == client_core::phase::playing);
    CHECK(core.player_id() == 3);
    CHECK(core.entity_id() == 7);
    CHECK(shared.playing() == 1);
}

TEST_CASE("a Welcome whose config hash does not match ends the session as a protocol error", "[client_core]") {
    protocol::welcome_info w = welcome_for(*world::preset_by_name("asteroids"));
    w.world_config_hash ^= 1;
    client_shared shared;
    client_core core(shared, params("b"));
    core.launch(0);
    core.connected();
    core.on_frame(protocol::encode_welcome(w), ms);
    REQUIRE(core.ended());
    CHECK(core.outcome().protocol_error);
    CHECK(core.outcome().failed());
    CHECK(core.outcome().reason == "Welcome: world_config_hash does not match world_config");
    CHECK(shared.ended() == 1);
    CHECK(shared.metrics().disconnects.at(core.outcome().reason) == 1);
}

TEST_CASE("a message that is not exactly one frame is refused", "[client_core]") {
    joined_core c;
    protocol::frame_bytes two = protocol::encode_pong(1, 2);
    const protocol::frame_bytes second = protocol::encode_pong(3, 4);
    two.insert(two.end(), second.begin(), second.end());
    c.core.on_frame(two, 20 * ms);
    REQUIRE(c.core.ended());
    CHECK(c.core.outcome().reason == "a message from the server that is not exactly one frame");
}

TEST_CASE("each tick sends one Input, numbered from 1, and a Ping once a second", "[client_core]") {
    joined_core c;
    std::vector<protocol::frame_bytes> frames;
    std::uint32_t pings = 0;
    for (std::uint64_t tick = 1; tick <= 120; ++tick) {
        c.core.on_tick(tick, tick * 16 * ms);
        frames.clear();
        for (const Payload type : drain(c.core, &frames)) pings += type == Payload::Ping;
        const auto input = protocol::decode_input(*protocol::verify_message(frames[0]).value);
        REQUIRE(input.ok());
        CHECK(input.value.sequence == tick);
    }
    CHECK(pings == 2);  // (tick + index) % 60 == 0 with index 1: ticks 59 and 119
    CHECK(c.core.prediction()->last_sequence() == 120);
}

TEST_CASE("the round trip is measured on the time the core is given", "[client_core]") {
    joined_core c;
    c.snapshot(101, 0, 15 * ms);
    c.core.on_frame(protocol::encode_pong(1000 * ms, 150), 1042 * ms);
    REQUIRE(c.shared.metrics().rtt_ms.size() == 1);
    CHECK(c.shared.metrics().rtt_ms.summarize().max == Approx(42.0));
    // A Pong from the future is not one we sent: not measured.
    c.core.on_frame(protocol::encode_pong(5000 * ms, 151), 1100 * ms);
    CHECK(c.shared.metrics().rtt_ms.size() == 1);
}

TEST_CASE("a Pong that says how long the server held the Ping splits the round trip", "[client_core]") {
    // 17 ms on loopback was the server's wait for its next tick's read, not the network's.
    joined_core c;
    c.snapshot(101, 0, 15 * ms);
    c.core.on_frame(protocol::encode_pong(1000 * ms, 150, 16'500), 1017 * ms);
    const auto& m = c.shared.metrics();
    REQUIRE(m.server_hold_ms.size() == 1);
    CHECK(c.shared.metrics().server_hold_ms.summarize().max == Approx(16.5));
    CHECK(c.shared.metrics().network_rtt_ms.summarize().max == Approx(0.5));
    CHECK(c.shared.metrics().rtt_ms.summarize().max == Approx(17.0));
    // A Pong without it (WebSocket, UDP, an older server): the round trip alone.
    c.core.on_frame(protocol::encode_pong(1100 * ms, 151), 1117 * ms);
    CHECK(m.rtt_ms.size() == 2);
    CHECK(m.server_hold_ms.size() == 1);
}

TEST_CASE("an ack_sequence that goes back ends the session", "[client_core]") {
    joined_core c;
    for (std::uint64_t tick = 1; tick <= 10; ++tick) c.core.on_tick(tick, tick * 16 * ms);
    c.snapshot(110, 0, 160 * ms);
    c.snapshot(113, 6, 210 * ms);
    CHECK(c.core.last_ack() == 6);
    REQUIRE_FALSE(c.core.ended());
    c.snapshot(116, 5, 260 * ms);
    REQUIRE(c.core.ended());
    CHECK(c.core.outcome().reason == "Snapshot: ack_sequence went back");
    CHECK(c.core.last_ack() == 6);
}

// The check the browser's session made and the bots' did not, until both ran one session.
TEST_CASE("a snapshot whose tick goes back on a stream ends the session, as it ends the browser's", "[client_core]") {
    joined_core c;
    c.core.on_tick(1, 16 * ms);
    c.snapshot(110, 1, 100 * ms);
    REQUIRE_FALSE(c.core.ended());
    c.snapshot(110, 1, 150 * ms);
    REQUIRE(c.core.ended());
    CHECK(c.core.outcome().protocol_error);
    CHECK(c.core.outcome().reason == "Snapshot: tick went back");
    CHECK(c.core.server_session().error() == "Snapshot: tick went back");
}

TEST_CASE("an ack of an input never sent ends the session", "[client_core]") {
    joined_core c;
    c.core.on_tick(1, 16 * ms);
    c.snapshot(110, 2, 100 * ms);
    REQUIRE(c.core.ended());
    CHECK(c.core.outcome().reason == "Snapshot: ack_sequence acknowledges an input never sent");
}

TEST_CASE("finish says Bye and ends once the transport wrote it", "[client_core]") {
    joined_core c;
    c.shared.set_stopping();
    c.core.finish();
    CHECK(c.core.closing());
    REQUIRE(drain(c.core) == std::vector{Payload::Bye});
    CHECK_FALSE(c.core.ended());
    c.core.on_tick(5, 100 * ms);  // no more inputs once closing
    CHECK(c.core.output().empty());
    c.core.flushed();
    REQUIRE(c.core.ended());
    CHECK_FALSE(c.core.outcome().ended_early);
    CHECK_FALSE(c.core.outcome().failed());
}

TEST_CASE("no Welcome within the join timeout gives up", "[client_core]") {
    client_shared shared;
    client_params p = params("b");
    p.join_timeout = 2000 * ms;
    client_core core(shared, p);
    core.launch(1000 * ms);
    core.connected();
    core.check_join_timeout(2999 * ms);
    CHECK_FALSE(core.ended());
    core.check_join_timeout(3000 * ms);
    REQUIRE(core.ended());
    CHECK(core.outcome().reason == "no Welcome in time");
    CHECK(core.outcome().failed());
}

TEST_CASE("the slow-reader fault stops reading once playing", "[client_core]") {
    client_shared shared;
    client_params p = params("b");
    p.mode = misbehavior::slow_reader;
    client_core core(shared, p);
    core.launch(0);
    core.connected();
    CHECK(core.reading());
    core.on_frame(protocol::encode_welcome(welcome_for(*world::preset_by_name("asteroids"))), ms);
    CHECK_FALSE(core.reading());
}

TEST_CASE("on datagrams a snapshot that overtook the Welcome, or an older one, is dropped", "[client_core]") {
    client_shared shared;
    client_params p = params("b");
    p.unordered = true;
    client_core core(shared, p);
    core.launch(0);
    core.connected();
    flatbuffers::FlatBufferBuilder fbb;
    const protocol::BodyState own(7, 3, 100, 100, 1, 0, 0, 0);
    const auto early = protocol::encode_snapshot(fbb, 101, 0, {&own, 1});
    core.on_frame(early, ms);
    REQUIRE(core.current() == client_core::phase::joining);
    CHECK(shared.metrics().stale_messages == 1);
    core.on_frame(protocol::encode_welcome(welcome_for(*world::preset_by_name("asteroids"))), 2 * ms);
    REQUIRE(core.current() == client_core::phase::playing);
    for (std::uint64_t tick = 1; tick <= 6; ++tick) core.on_tick(tick, tick * 16 * ms);
    core.on_frame(protocol::encode_snapshot(fbb, 110, 4, {&own, 1}), 100 * ms);
    CHECK(core.snapshots() == 1);
    // A duplicate, then one overtaken (older tick, older ack): both dropped, the session goes on.
    core.on_frame(protocol::encode_snapshot(fbb, 110, 4, {&own, 1}), 101 * ms);
    core.on_frame(protocol::encode_snapshot(fbb, 107, 2, {&own, 1}), 102 * ms);
    CHECK_FALSE(core.ended());
    CHECK(core.snapshots() == 1);
    CHECK(core.last_ack() == 4);
    CHECK(shared.metrics().stale_messages == 3);
}
