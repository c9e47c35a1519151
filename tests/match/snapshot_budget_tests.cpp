// Delta snapshots under a per-client byte budget (UDP: one datagram each, never fragmented):
// a crowded view goes out in parts chosen by the priority accumulator, the client keeps the
// bodies left out as predicted, and every frame still decodes against its baseline (the
// checksum proves the server's record of what the client holds is exact).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <map>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "games/asteroids/asteroids_rules.hpp"
#include "match/drive.hpp"
#include "protocol/decode.hpp"
#include "protocol/delta/quantize.hpp"
#include "protocol/delta/receiver.hpp"
#include "protocol/game.hpp"
#include "protocol/shapes.hpp"
#include "protocol/verify.hpp"
#include "server/match/body_state.hpp"
#include "server/match/match.hpp"
#include "server/match/snapshot_fanout.hpp"
#include "server/match/snapshot_priority.hpp"
#include "server/world/presets.hpp"
#include "server/world/world.hpp"

using namespace arena;
using protocol::delta::quantized_body;

namespace {

constexpr uint16_t tick_rate = 60;
constexpr uint32_t interval = 3;  // 20 snapshots a second
constexpr size_t datagram = 1200;

// 300 rocks and a ship in the asteroids world, falling: under gravity every body's velocity
// changes between two snapshots, so a body the client holds as predicted differs from the
// truth until a frame refreshes it (a drifting rock would be predicted exactly).
world::world_config crowded() {
    world::world_config c = world::asteroids_preset();
    c.rocks.count = 300;
    c.gravity = {0, -3};
    return c;
}

protocol::snapshot_view read_snapshot(const std::vector<uint8_t>& frame) {
    auto message = protocol::verify_message(frame, protocol::server_frame_limits);
    REQUIRE(message);
    auto snapshot = protocol::decode_snapshot(*message.value);
    INFO(snapshot.error);
    REQUIRE(snapshot);
    return snapshot.value;
}

// One client of the fan-out, driven without a match: it loses every `lose_every`-th frame.
struct budget_run {
    explicit budget_run(size_t budget, uint32_t lose_every = 0) : lose_every(lose_every), client(ring, true, budget) {
        own = *w.spawn_player(world::player_id{1});
        for (const world::body& b : w.bodies())
            kinds.set(b.id, b.id == own.value() ? rules::kind_ship : rules::kind_rock);
        client.shapes.welcomed(0);
    }

    // Steps to the next snapshot and sends it; returns the frame's bytes.
    std::vector<uint8_t> next() {
        for (uint32_t k = 0; k < interval; ++k) w.step({});
        fanout.begin(w, &kinds);
        const auto frame = fanout.delta_frame(client, own, 0);
        ++sent;
        return {frame.begin(), frame.end()};
    }

    // Decodes a frame as the client does; returns its view (empty when the frame was lost).
    std::vector<quantized_body> deliver(const std::vector<uint8_t>& frame) {
        if (lose_every != 0 && sent % lose_every == 0) return {};
        const protocol::snapshot_view s = read_snapshot(frame);
        std::vector<protocol::shape_desc> got;
        REQUIRE(protocol::read_shapes(s.shapes, s.shape_vertices, got).empty());
        for (const protocol::shape_desc& d : got) shapes[d.id] = d.kind;
        auto decoded = rx.receive(s);
        INFO("snapshot " << s.tick << " against " << s.baseline_tick << ": " << decoded.error);
        REQUIRE(decoded);
        client.acked_tick = rx.ack();  // the next Input carries it at once
        std::vector<quantized_body> view(decoded.value.begin(), decoded.value.end());
        // The client holds the shape of every body of the view it decoded.
        std::erase_if(shapes, [&](const auto& kv) {
            return !std::ranges::any_of(view, [&](const quantized_body& b) { return b.id == kv.first; });
        });
        for (const quantized_body& b : view) REQUIRE(shapes.contains(b.id));
        return view;
    }

    quantized_body truth(uint32_t id) const { return protocol::delta::quantize(match::body_state(*w.find(id))); }

    uint32_t lose_every;
    world::world w{crowded(), 7};
    match::body_kinds kinds;
    world::body_id own;
    match::tick_ring ring{32, interval};
    match::snapshot_fanout fanout{{0, ring, tick_rate}};
    match::snapshot_client client;
    protocol::delta::receiver rx{tick_rate};
    std::map<uint32_t, uint8_t> shapes;
    uint32_t sent = 0;
};

}  // namespace

// The falling scene costs about 3 bytes a body once the client holds it, 900 bytes in all:
// a datagram holds the whole view after the join (whose frames carry the bodies in full, and
// their shapes), a 500-byte budget never does.
TEST_CASE("a crowded view over a byte budget: every frame fits, every body is refreshed in turn", "[match][budget]") {
    const size_t budget = GENERATE(as<size_t>(), 1200, 500);
    const uint32_t lose_every = GENERATE(0u, 5u);
    INFO("budget " << budget << ", losing every " << lose_every << "th frame");
    budget_run run(budget, lose_every);
    REQUIRE(run.w.bodies().size() == 301);
    std::map<uint32_t, uint32_t> fresh_at;  // body id → the last decoded snapshot that held it exactly
    uint32_t decoded = 0, most_stale = 0, filled_at = 0;
    for (int n = 0; n < 250; ++n) {
        const std::vector<uint8_t> frame = run.next();
        REQUIRE(frame.size() <= budget);
        const std::vector<quantized_body> view = run.deliver(frame);
        if (view.empty()) continue;
        ++decoded;
        // The own ship is in every frame, exact.
        const auto own = std::ranges::find(view, run.own.value(), &quantized_body::id);
        REQUIRE(own != view.end());
        CHECK(*own == run.truth(run.own.value()));
        for (const quantized_body& b : view) {
            if (b == run.truth(b.id)) fresh_at[b.id] = decoded;
        }
        // Joining: the view fills over the first frames (new bodies go in full, with their
        // shapes); once whole, every body of the world stays in the client's view (kept, not
        // removed) and is exact within the last few decoded frames.
        if (filled_at == 0 && view.size() == run.w.bodies().size()) filled_at = decoded;
        if (filled_at == 0) continue;
        REQUIRE(view.size() == run.w.bodies().size());
        if (decoded < filled_at + 30) continue;  // the bodies the join left out get their turn
        for (const quantized_body& b : view) most_stale = std::max(most_stale, decoded - fresh_at[b.id]);
    }
    INFO("the view filled at decoded snapshot " << filled_at);
    REQUIRE(filled_at != 0);
    CHECK(filled_at <= (budget == 1200 ? 30u : 80u));
    INFO("most decoded snapshots a body waited for a refresh: " << most_stale);
    CHECK(most_stale <= 8);
    const match::fanout_counters& c = run.fanout.counters();
    CHECK(c.trimmed_frames >= 20);
    if (budget < 900) CHECK(c.trimmed_frames == 250);
    CHECK(c.left_out_bodies > 0);
    CHECK(run.client.priorities.most_left_out() <= 8);
}

TEST_CASE("without a budget the same view goes whole, in frames larger than a datagram", "[match][budget]") {
    budget_run run(0);
    size_t largest = 0;
    for (int n = 0; n < 20; ++n) {
        const std::vector<uint8_t> frame = run.next();
        largest = std::max(largest, frame.size());
        CHECK(run.deliver(frame).size() == run.w.bodies().size());
    }
    CHECK(largest > datagram);
    CHECK(run.fanout.counters().trimmed_frames == 0);
}

TEST_CASE("a view that fits the budget goes whole, untrimmed", "[match][budget]") {
    budget_run run(64 * 1024);
    for (int n = 0; n < 20; ++n) CHECK(run.deliver(run.next()).size() == run.w.bodies().size());
    CHECK(run.fanout.counters().trimmed_frames == 0);
}

TEST_CASE("budgeted frames are a pure function of the world and the client's acks", "[match][budget]") {
    budget_run a(datagram, 4), b(datagram, 4);
    for (int n = 0; n < 60; ++n) {
        const std::vector<uint8_t> fa = a.next(), fb = b.next();
        REQUIRE(fa == fb);
        a.deliver(fa);
        b.deliver(fb);
    }
}

TEST_CASE("priority: the own body first, then near and important bodies, and a left-out body climbs",
          "[match][budget]") {
    world::world_config config = world::asteroids_preset();
    config.rocks.count = 0;
    world::world w(config, 1);
    const world::body_id own = *w.spawn_player(world::player_id{1});
    const world::vec2 at = w.find(own)->position;
    auto add = [&](float dx) {
        world::body b;
        b.position = at + world::vec2{dx, 0};
        b.radius = 1;
        return *w.add_body(b);
    };
    const uint32_t near_rock = add(5), far_rock = add(150), far_ship = add(-150);
    match::body_kinds kinds;
    kinds.set(own.value(), rules::kind_ship);
    kinds.set(near_rock, rules::kind_rock);
    kinds.set(far_rock, rules::kind_rock);
    kinds.set(far_ship, rules::kind_ship);
    const rules::asteroids_rules game(w);  // the weights a match takes from its game's rules
    for (const uint8_t kind : {rules::kind_ship, rules::kind_rock}) kinds.set_weight(kind, game.snapshot_weight(kind));
    std::vector<uint32_t> view;
    for (uint32_t i = 0; i < w.bodies().size(); ++i) view.push_back(i);

    match::priority_accumulator p;
    p.accumulate(w.bodies(), view, own.value(), kinds, w.config());
    std::vector<uint32_t> order;
    for (const uint32_t k : p.ranked()) order.push_back(w.bodies()[view[k]].id);
    CHECK(order == std::vector<uint32_t>{own.value(), far_ship, near_rock, far_rock});
    CHECK(kinds.weight_of(far_ship) == 4);
    CHECK(kinds.weight_of(far_rock) == 1);
    CHECK(match::priority_accumulator::gain(1, 0) > match::priority_accumulator::gain(1, 1e4f));
    CHECK(match::priority_accumulator::gain(4, 1e6f) > match::priority_accumulator::gain(1, 1e6f));

    // Only two go in each time, so the far rock shares one place with bodies whose gains are
    // 4 and 3.5 times its own: it waits about (sum of the three gains) / its gain, 8.5 frames.
    uint32_t far_rock_waited = 0;
    for (int n = 0; n < 20; ++n) {
        std::vector<uint8_t> chosen(view.size(), 0);
        chosen[p.ranked()[0]] = chosen[p.ranked()[1]] = 1;
        p.sent(chosen);
        far_rock_waited = std::max(far_rock_waited, p.left_out_of(far_rock));
        CHECK(p.priority_of(own.value()) == 0);
        p.accumulate(w.bodies(), view, own.value(), kinds, w.config());
    }
    CHECK(far_rock_waited >= 5);
    CHECK(far_rock_waited <= 9);
    CHECK(p.most_left_out() <= 9);
}

namespace {

// A connection with a datagram's budget, as the UDP transport's peers have.
struct datagram_client : match::connection {
    std::vector<std::vector<uint8_t>> snapshots;
    void send(protocol::frame_bytes) override {}
    void send_snapshot(const protocol::snapshot_encoder& s, uint32_t ack) override {
        snapshots.push_back(s.frame_with_ack(ack));
    }
    void send_snapshot_frame(std::span<const uint8_t> frame) override {
        snapshots.emplace_back(frame.begin(), frame.end());
    }
    void close(protocol::RejectCode, std::string_view) override {}
    void close_with_bye(std::string_view) override {}
    std::string_view peer() const override { return "test"; }
    size_t snapshot_budget() const override { return budget; }
    size_t budget = datagram;
};

// An Asteroids match at the tests' rates.
match::match asteroids_match(uint32_t max_players = match::match_config{}.admission.max_players) {
    match::match_config config;
    config.tick_rate = tick_rate;
    config.snapshot_rate = tick_rate / interval;
    config.admission.max_players = max_players;
    world::world_config world = world::asteroids_preset();
    world.rules = "asteroids";
    return match::match(config, world);
}

// Joins every client, asking for delta snapshots, as NAME_PREFIX followed by its index.
void join_each(match::match& g, std::vector<datagram_client>& clients, const std::string& name_prefix) {
    for (size_t k = 0; k < clients.size(); ++k) {
        std::string name = name_prefix;
        name += std::to_string(k);
        REQUIRE(match_test::join(g, clients[k], {protocol::protocol_version, name, "", true}) != 0);
    }
}

}  // namespace

TEST_CASE("the match takes each connection's budget: datagram clients trimmed, stream clients whole",
          "[match][budget]") {
    match::match_config config;
    config.tick_rate = tick_rate;
    config.snapshot_rate = tick_rate / interval;
    world::world_config world = crowded();
    match::match g(config, world);
    datagram_client udp, tcp;
    tcp.budget = 0;
    REQUIRE(match_test::join(g, udp, {protocol::protocol_version, "udp", "", true}) != 0);
    REQUIRE(match_test::join(g, tcp, {protocol::protocol_version, "tcp", "", true}) != 0);
    for (int k = 0; k < 30; ++k) g.tick();
    REQUIRE(!udp.snapshots.empty());
    REQUIRE(!tcp.snapshots.empty());
    for (const auto& f : udp.snapshots) CHECK(f.size() <= datagram);
    CHECK(std::ranges::any_of(tcp.snapshots, [](const auto& f) { return f.size() > datagram; }));
    CHECK(g.counters().snapshots.trimmed_frames == udp.snapshots.size());
}

TEST_CASE("32 players' names and lines go over a few datagrams, each frame within the budget",
          "[match][budget][game]") {
    match::match g = asteroids_match(32);
    std::vector<datagram_client> clients(32);
    join_each(g, clients, "pilot-with-a-long-name-");
    // Every client acknowledges what it decoded but client 0, which hears nothing back.
    std::vector<uint32_t> sequence(clients.size(), 0), acked(clients.size(), 0);
    std::vector<std::set<uint32_t>> names(clients.size());
    std::vector<size_t> read(clients.size(), 0);
    for (int t = 0; t < 60; ++t) {
        g.tick();
        for (size_t k = 0; k < clients.size(); ++k) {
            for (; read[k] < clients[k].snapshots.size(); ++read[k]) {
                const auto& frame = clients[k].snapshots[read[k]];
                CHECK(frame.size() <= datagram);
                const protocol::snapshot_view s = read_snapshot(frame);
                protocol::game_list game;
                REQUIRE(protocol::read_game(*s.table, game).empty());
                names[k].insert(game.name_ids.begin(), game.name_ids.end());
                acked[k] = s.tick;
            }
            protocol::input_msg in;
            in.sequence = ++sequence[k];
            in.snapshot_ack = k == 0 ? 0 : acked[k];
            REQUIRE(match_test::send_input(g, clients[k], in));
        }
    }
    for (size_t k = 1; k < clients.size(); ++k) CHECK(names[k].size() == 32);
    CHECK(read[0] > 0);  // the silent client got its frames, each within the budget too
}

TEST_CASE("a client whose snapshots were lost for longer than the baselines last is not sent the game again",
          "[match][budget][game]") {
    match::match g = asteroids_match();
    std::vector<datagram_client> clients(4);
    join_each(g, clients, "player-");
    uint32_t sequence = 0, acked = 0;
    size_t read = 0;
    // Names carried by the snapshots client 0 decodes from `from` on.
    const auto names_after = [&](size_t from) {
        size_t names = 0;
        for (size_t n = from; n < clients[0].snapshots.size(); ++n) {
            protocol::game_list game;
            REQUIRE(protocol::read_game(*read_snapshot(clients[0].snapshots[n]).table, game).empty());
            names += game.names.size();
        }
        return names;
    };
    const auto play = [&](int ticks, bool hears) {
        for (int t = 0; t < ticks; ++t) {
            g.tick();
            if (hears)
                for (; read < clients[0].snapshots.size(); ++read)
                    acked = read_snapshot(clients[0].snapshots[read]).tick;
            read = clients[0].snapshots.size();
            for (size_t k = 0; k < clients.size(); ++k) {
                protocol::input_msg in;
                in.sequence = ++sequence;  // one count for all: each client's inputs still go up
                in.snapshot_ack = k == 0 ? acked : 0;
                REQUIRE(match_test::send_input(g, clients[k], in));
            }
        }
    };
    play(30, true);
    REQUIRE(names_after(0) >= 4);  // it learnt every name
    // 3 s without a snapshot: longer than the 32 baselines kept (1.6 s), so its ack names one
    // that is gone.
    play(180, false);
    const size_t from = clients[0].snapshots.size();
    play(30, true);
    CHECK(clients[0].snapshots.size() > from);
    CHECK(names_after(from) == 0);
}
