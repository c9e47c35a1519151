// The golden recording: a scripted 600-tick asteroids session with five players (see
// scripted_session.hpp), replayed with every hash matching. When the physics change on
// purpose, regenerate it (server/replay/README.md) in the same commit and say why.
#include <catch2/catch.hpp>

#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "replay_files.hpp"
#include "server/replay/replayer.hpp"
#include "server/world/world.hpp"

using namespace arena::replay;

namespace {

constexpr uint64_t golden_final_hash = 0x308927a346773945ULL;
constexpr uint32_t golden_ticks = 600;

std::vector<std::pair<uint32_t, uint64_t>> replay_hashes(const std::string& path, replay_report& report) {
    auto opened = replayer::open(path);
    REQUIRE(opened.ok());
    std::vector<std::pair<uint32_t, uint64_t>> hashes;
    replay_options options;
    options.on_tick = [&](uint32_t tick, uint64_t hash) {
        hashes.emplace_back(tick, hash);
    };
    report = opened.value->run(options);
    return hashes;
}

// A recording of the scripted session (scripted_session.hpp) replays whole, every hash matching.
void check_scripted_replay(replayer& replay, uint64_t final_hash) {
    const replay_report report = replay.run();
    INFO(report.error);
    CHECK(report.error.empty());
    CHECK_FALSE(report.mismatch.has_value());
    CHECK(report.complete);
    CHECK(report.ticks_replayed == golden_ticks);
    // The start hash, a Hash record every 60 ticks and the End record.
    CHECK(report.hashes_checked == 1 + golden_ticks / 60 + 1);
    CHECK(report.final_tick == golden_ticks);
    CHECK(report.final_hash == final_hash);
}

}  // namespace

TEST_CASE("the golden recording replays with every hash matching and the expected final hash", "[replay][golden]") {
    auto opened = replayer::open(testing::golden_path());
    REQUIRE(opened.ok());
    CHECK(opened.value->file_header().preset == "asteroids");
    // Recorded under world version 2; versions 3 and 4 changed only chains and sub-steps, which it
    // has none of.
    CHECK(opened.value->file_header().world_version == 2);
    check_scripted_replay(*opened.value, golden_final_hash);
}

TEST_CASE("replaying the same recording twice gives identical hashes at every tick", "[replay][golden]") {
    replay_report first_report, second_report;
    const auto first = replay_hashes(testing::golden_path(), first_report);
    const auto second = replay_hashes(testing::golden_path(), second_report);
    REQUIRE(first.size() == golden_ticks + 1);
    CHECK(first == second);
    CHECK(first.back().second == golden_final_hash);
}

// The golden recording as world version 1 wrote it (circles only, frictionless contacts),
// kept to prove that a recording of other physics is refused, not replayed into mismatches.
TEST_CASE("a world version 1 recording is refused with a message naming both versions", "[replay][golden]") {
    auto opened = replayer::open(std::string(ARENA_TEST_DATA_DIR) + "/golden_asteroids_world_v1.arpl");
    REQUIRE_FALSE(opened.ok());
    INFO(opened.error);
    CHECK(opened.error.find("recorded with world version 1") != std::string::npos);
    CHECK(opened.error.find("this build simulates world version " + std::to_string(arena::world::world_version)) !=
          std::string::npos);
}

// A live Asteroids match under the game's rules, recorded by arena-server from six hunter bots
// for 12 s: ships fire, rocks split, ships die and respawn. The rules' state is in every
// recorded hash, so the replay reproduces the scores bit for bit; scripts/determinism-check.sh
// replays it from every compiler and architecture too. Its scoreboard is the one the live
// server wrote to --stats-json (names were not recorded then: tests/e2e/game_e2e_tests.cpp
// compares a new recording's, names included).
TEST_CASE("the golden Asteroids match replays to the live scoreboard with every hash matching", "[replay][golden]") {
    auto opened = replayer::open(std::string(ARENA_TEST_DATA_DIR) + "/golden_asteroids_rules.arpl");
    REQUIRE(opened.ok());
    const replay_report report = opened.value->run();
    INFO(report.error);
    CHECK(report.error.empty());
    CHECK_FALSE(report.mismatch.has_value());
    CHECK(report.complete);
    CHECK(report.final_tick == 719);
    CHECK(report.hashes_checked == 13);
    CHECK(report.final_hash == 0xa1d03817af7c96b3ULL);
    struct expected_line {
        uint32_t player, score, kills, deaths, shots, hits;
    };
    const expected_line live[] = {{1, 640, 0, 1, 14, 10}, {2, 790, 0, 0, 27, 11}, {3, 620, 0, 0, 14, 8},
                                  {4, 390, 0, 1, 9, 7},   {5, 270, 0, 1, 9, 4},   {6, 840, 0, 0, 21, 12}};
    const auto lines = opened.value->game_rules().scoreboard();
    REQUIRE(lines.size() == std::size(live));
    for (size_t i = 0; i < lines.size(); ++i) {
        INFO("player " << live[i].player);
        CHECK(lines[i].player == live[i].player);
        CHECK(lines[i].score == live[i].score);
        CHECK(lines[i].kills == live[i].kills);
        CHECK(lines[i].deaths == live[i].deaths);
        CHECK(lines[i].shots == live[i].shots);
        CHECK(lines[i].hits == live[i].hits);
    }
}

// The same scripted session in the pyramid preset (tests/replay/make_golden.cpp): 210 boxes
// stacked in 4 sub-steps, so the sub-stepped solver's colouring and its lanes are in every
// hash; scripts/determinism-check.sh and the WebAssembly replay test replay it too.
TEST_CASE("the golden sub-stepped pyramid replays with every hash matching", "[replay][golden]") {
    auto opened = replayer::open(std::string(ARENA_TEST_DATA_DIR) + "/golden_pyramid.arpl");
    REQUIRE(opened.ok());
    CHECK(opened.value->file_header().preset == "pyramid");
    CHECK(opened.value->file_header().world_version == 4);
    CHECK(opened.value->state().config().substeps == 4);
    check_scripted_replay(*opened.value, 0xddafdd7ad04e0975ULL);
}

TEST_CASE("a replay stopped at its `until` goes on from there: the same hashes as one run", "[replay][golden]") {
    replay_report whole;
    const auto expected = replay_hashes(testing::golden_path(), whole);

    auto opened = replayer::open(testing::golden_path());
    REQUIRE(opened.ok());
    replayer& rp = *opened.value;
    std::vector<std::pair<uint32_t, uint64_t>> hashes;
    replay_options options;
    options.on_tick = [&](uint32_t tick, uint64_t hash) {
        hashes.emplace_back(tick, hash);
    };
    uint32_t checked = 0;
    uint32_t stepped = 0;
    // Stops on and off a Hash record's tick, twice at the same tick, then to the end.
    for (const uint32_t until : {0u, 1u, 60u, 60u, 61u, 299u, 600u}) {
        options.until = until;
        const replay_report part = rp.run(options);
        INFO("until " << until << ": " << part.error);
        REQUIRE(part.complete);
        REQUIRE_FALSE(part.mismatch.has_value());
        CHECK(part.final_tick == until);
        checked += part.hashes_checked;
        stepped += part.ticks_replayed;
    }
    CHECK(hashes == expected);
    CHECK(checked == whole.hashes_checked);
    CHECK(stepped == whole.ticks_replayed);

    options.until = 30;
    CHECK(rp.run(options).error == "tick 30 is before the replay's tick 600");
    options.until = 601;
    CHECK(rp.run(options).error == "tick 601 is after the recording's end at tick 600");
    options.until.reset();
    const replay_report after_end = rp.run(options);
    CHECK(after_end.complete);
    CHECK(after_end.ticks_replayed == 0);
    CHECK(after_end.final_hash == golden_final_hash);
}
