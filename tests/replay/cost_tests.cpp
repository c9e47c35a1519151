// Replay files from strangers cannot ask for more work than a real recording: the empty steps
// up to start_tick, the tick rate and a tick's joins are bounded by what arena-server can
// record, and many joins in one tick spawn in linear time.
#include <catch2/catch.hpp>
#include <string>
#include <tuple>
#include <vector>

#include "common/run_command.hpp"
#include "replay_files.hpp"
#include "server/match/tick_record.hpp"
#include "server/replay/record_format.hpp"
#include "server/world/presets.hpp"

using namespace arena;
using namespace arena::replay;
using testing::temp_file;
using testing::write_bytes;

namespace {

header asteroids_header() {
    world::world w(world::asteroids_preset(), 1);
    return make_header(w, "asteroids", 1, 60);
}

// arena-replay on `path`, stopped after `seconds` whatever the file asks for (exit 124 then).
arena::test::command_result run_replay(const std::string& path, int seconds) {
    return arena::test::run_command("timeout " + std::to_string(seconds) + " " + arena::test::program("arena-replay") +
                                    " " + path + " 2>&1 >/dev/null");
}

// A recording of `h` and its end, nothing between, written to `path` and replayed.
arena::test::command_result replay_header_alone(const std::string& path, const header& h) {
    record_encoder encoder;
    std::vector<uint8_t> bytes;
    encoder.append(h, bytes);
    encoder.append(end_marker{0, h.start_hash}, bytes);
    write_bytes(path, bytes);
    return run_replay(path, 20);
}

}  // namespace

TEST_CASE("a start_tick far past a server's first tick is refused before any step", "[replay][cost]") {
    // A 1.2 KB file whose header asked for 4.3 billion empty steps before the first check.
    temp_file file("far-start");
    header h = asteroids_header();
    h.start_tick = 0xFFFFFFFFu;
    record_encoder encoder;
    std::vector<uint8_t> bytes;
    encoder.append(h, bytes);
    encoder.append(end_marker{h.start_tick, h.start_hash}, bytes);
    write_bytes(file.path(), bytes);
    const auto r = run_replay(file.path(), 20);
    CHECK(r.exit_code == 2);
    CHECK(r.output == "arena-replay: " + file.path() +
                          ": byte offset 0: Header: start_tick 4294967295 is more than 60 s (3600 ticks at 60 Hz) "
                          "after the world's start: arena-server records from a match's first tick\n");

    // A minute of empty ticks is still replayed (and its start hash checked).
    world::world w(world::asteroids_preset(), 1);
    for (int k = 0; k < 3600; ++k) w.step({});
    header late = asteroids_header();
    late.start_tick = 3600;
    late.start_hash = w.hash();
    bytes.clear();
    encoder.append(late, bytes);
    encoder.append(end_marker{3600, w.hash()}, bytes);
    write_bytes(file.path(), bytes);
    CHECK(run_replay(file.path(), 20).exit_code == 0);
}

TEST_CASE("a header whose config asks for 30 million rocks is refused before any work", "[replay][cost]") {
    // The header's config used to be accepted, and arena-replay placed a million rocks (more
    // than 20 s) before it read a tick.
    temp_file file("many-rocks");
    header h = asteroids_header();
    const std::string count = "\"count\": 40";
    const size_t at = h.world_config.find(count);
    REQUIRE(at != std::string::npos);
    h.world_config.replace(at, count.size(), "\"count\": 30000000");
    const auto r = replay_header_alone(file.path(), h);
    CHECK(r.exit_code == 2);
    CHECK(r.output == "arena-replay: " + file.path() +
                          ": byte offset 0: Header: world config: field 'rocks.count' must be at most 1048576, got "
                          "30000000\n");
}

TEST_CASE("a header whose game parameters the game refuses is refused before any work", "[replay][cost]") {
    temp_file file("bad-params");
    header h = asteroids_header();
    const size_t end = h.world_config.rfind('}');
    REQUIRE(end != std::string::npos);
    h.world_config.replace(end, 1, R"(, "rules": "asteroids", "rules_params": {"lives": 5000}})");
    const auto r = replay_header_alone(file.path(), h);
    CHECK(r.exit_code == 2);
    CHECK(r.output == "arena-replay: " + file.path() +
                          ": byte offset 0: Header: world config: rules_params.lives must be a whole number in [0, "
                          "1000]\n");
}

TEST_CASE("a header with a rate no server runs at is refused", "[replay][cost]") {
    temp_file file("rates");
    record_encoder encoder;
    for (const auto& [rate, interval, reason] :
         {std::tuple{5000u, 60u, "Header: tick_rate 5000 is outside [1, 1000]"},
          std::tuple{60u, 2000000u, "Header: hash_interval 2000000 is outside [1, 1000000]"}}) {
        header h = asteroids_header();
        h.tick_rate = rate;
        h.hash_interval = interval;
        std::vector<uint8_t> bytes;
        encoder.append(h, bytes);
        encoder.append(end_marker{0, h.start_hash}, bytes);
        write_bytes(file.path(), bytes);
        const auto r = run_replay(file.path(), 20);
        CHECK(r.exit_code == 2);
        CHECK(r.output.find(std::string("byte offset 0: ") + reason) != std::string::npos);
    }
}

TEST_CASE("30 000 joins in one tick replay in linear time, and more than a server admits are refused",
          "[replay][cost]") {
    // 120 KB of joins took 18 s: each spawn tried 32 spots against every body already there.
    temp_file file("joins");
    const header h = asteroids_header();
    match::tick_record tick{0, {}, {}, {}, {}};
    for (uint32_t owner = 1; owner <= 30000; ++owner) tick.joins.emplace_back(owner);
    world::world w(world::asteroids_preset(), 1);
    match::apply_tick(w, tick);
    record_encoder encoder;
    std::vector<uint8_t> bytes;
    encoder.append(h, bytes);
    encoder.append(tick, bytes);
    encoder.append(end_marker{1, w.hash()}, bytes);
    write_bytes(file.path(), bytes);
    // A guard, not a benchmark: the quadratic spawn took 18 s here (and more under ASan).
    CHECK(run_replay(file.path(), 15).exit_code == 0);

    bytes.clear();
    encoder.append(h, bytes);
    const uint64_t offset = bytes.size();
    tick.joins.resize(max_joins_per_tick + 1, world::player_id{7});
    encoder.append(tick, bytes);
    encoder.append(end_marker{1, 0}, bytes);
    write_bytes(file.path(), bytes);
    const auto r = run_replay(file.path(), 20);
    CHECK(r.exit_code == 2);
    CHECK(r.output == "arena-replay: " + file.path() + ": byte offset " + std::to_string(offset) +
                          ": Tick record for tick 0 has 100001 joins; a server admits at most 100000 players\n");
}

TEST_CASE("a tick of 30 000 leaves replays in linear time", "[replay][cost]") {
    // Each leave erased one body and moved every body after it: 30 000 leaves in id order
    // moved about 5e10 bytes.
    temp_file file("leaves");
    const header h = asteroids_header();
    match::tick_record joins{0, {}, {}, {}, {}}, leaves{1, {}, {}, {}, {}};
    for (uint32_t owner = 1; owner <= 30000; ++owner) joins.joins.emplace_back(owner);
    world::world w(world::asteroids_preset(), 1);
    for (const world::body_id id : match::apply_tick(w, joins)) leaves.leaves.push_back(id);
    match::apply_tick(w, leaves);
    record_encoder encoder;
    std::vector<uint8_t> bytes;
    encoder.append(h, bytes);
    encoder.append(joins, bytes);
    encoder.append(leaves, bytes);
    encoder.append(end_marker{2, w.hash()}, bytes);
    write_bytes(file.path(), bytes);
    CHECK(w.bodies().size() == 40);                     // the rocks
    CHECK(run_replay(file.path(), 30).exit_code == 0);  // a guard, not a benchmark
}
