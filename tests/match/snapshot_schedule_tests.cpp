// When each delta client gets its snapshot (match_snapshots.cpp): players in groups of 16 ids,
// one group per tick of the snapshot interval in turn, so that a big match's encoding is spread
// over the interval and a small match, one group, builds all its snapshots on one tick.
#include <catch2/catch.hpp>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "match/drive.hpp"
#include "protocol/version.hpp"

using namespace arena;
using namespace arena::match_test;

namespace {

// Notes the match's tick whenever a snapshot frame is sent to it.
struct scheduled_client : quiet_client {
    explicit scheduled_client(const match::match& m) : m(m) {}
    const match::match& m;
    std::vector<uint32_t> snapshot_ticks;
    void send_snapshot(const protocol::snapshot_encoder&, uint32_t) override { snapshot_ticks.push_back(tick()); }
    void send_snapshot_frame(std::span<const uint8_t>) override { snapshot_ticks.push_back(tick()); }
    uint32_t tick() const { return m.state().tick(); }
};

struct schedule {
    std::vector<std::unique_ptr<scheduled_client>> clients;  // by player id − 1
    std::map<uint32_t, size_t> sent_per_tick;                // tick → snapshots sent in it
};

// `players` delta clients join one match at once; then 60 ticks of play.
schedule run(size_t players) {
    match::match_config config;
    config.tick_rate = 60;
    config.snapshot_rate = 20;
    config.admission.max_players = 64;
    match::match m(config, rockless_asteroids());
    schedule s;
    for (size_t i = 0; i < players; ++i) {
        s.clients.push_back(std::make_unique<scheduled_client>(m));
        protocol::hello_msg hello{protocol::protocol_version, std::string(1, 'p').append(std::to_string(i + 1)), "",
                                  true};
        REQUIRE(join(m, *s.clients.back(), hello) == i + 1);
    }
    for (int t = 0; t < 60; ++t) m.tick();
    for (const auto& c : s.clients)
        for (const uint32_t tick : c->snapshot_ticks) ++s.sent_per_tick[tick];
    return s;
}

}  // namespace

TEST_CASE("a small match's delta clients all get their snapshots on one tick", "[match][delta][schedule]") {
    const schedule s = run(8);
    std::set<uint32_t> phases;
    for (const auto& [tick, sent] : s.sent_per_tick) {
        CHECK(sent == 8);  // every player in the same tick
        phases.insert(tick % 3);
    }
    CHECK(phases.size() == 1);
    for (const auto& c : s.clients) CHECK(c->snapshot_ticks.size() >= 19);  // 20 per second, after the join
}

TEST_CASE("a big match's delta clients are spread over the interval in groups of 16 ids", "[match][delta][schedule]") {
    const schedule s = run(40);  // groups: players 1–16, 17–32, 33–40
    std::map<uint32_t, std::set<size_t>> per_phase;
    for (const auto& [tick, sent] : s.sent_per_tick) per_phase[tick % 3].insert(sent);
    REQUIRE(per_phase.size() == 3);  // every tick sends a share
    std::multiset<size_t> shares;
    for (const auto& [phase, sizes] : per_phase) {
        REQUIRE(sizes.size() == 1);  // the same share on every tick of a phase
        shares.insert(*sizes.begin());
    }
    CHECK(shares == std::multiset<size_t>{8, 16, 16});
    for (size_t i = 0; i < s.clients.size(); ++i) {
        INFO("player " << i + 1);
        const auto& ticks = s.clients[i]->snapshot_ticks;
        REQUIRE(ticks.size() >= 19);
        for (size_t k = 1; k < ticks.size(); ++k) CHECK(ticks[k] - ticks[k - 1] == 3);  // its rate kept
        // Players of one group share a tick.
        CHECK(ticks.front() % 3 == s.clients[i / 16 * 16]->snapshot_ticks.front() % 3);
    }
}
