// Sessions recorded through the recorder, as the server records them, replay bit for bit; a
// recording with a tampered hash names the tick; the recorder keeps its promises (whole seconds
// on disk while running, ticks one after another).
#include <catch2/catch.hpp>

#include <vector>

#include "replay_files.hpp"
#include "scripted_session.hpp"
#include "server/replay/reader.hpp"
#include "server/replay/recorder.hpp"
#include "server/replay/replayer.hpp"
#include "server/world/presets.hpp"

using namespace arena;
using namespace arena::replay;
using testing::session_script;
using testing::temp_file;

namespace {

replay_report replay_file(const std::string& path, std::vector<uint64_t>* hashes = nullptr,
                          std::optional<uint32_t> until = std::nullopt) {
    auto opened = replayer::open(path);
    REQUIRE(opened.ok());
    replay_options options;
    options.until = until;
    if (hashes)
        options.on_tick = [hashes](uint32_t, uint64_t hash) {
            hashes->push_back(hash);
        };
    return opened.value->run(options);
}

}  // namespace

TEST_CASE("a recorded platformer session replays with the recorded hash at every tick", "[replay]") {
    temp_file file("platformer_session");
    session_script script;
    script.preset = "platformer";
    script.world_seed = 77;
    script.script_seed = 3;
    const auto recorded = testing::record_scripted_session(file.path(), script);
    REQUIRE(recorded.ok());

    std::vector<uint64_t> replayed;
    const replay_report report = replay_file(file.path(), &replayed);
    INFO(report.error);
    CHECK(report.complete);
    CHECK_FALSE(report.mismatch.has_value());
    CHECK(report.hashes_checked == 1 + 600 / 60 + 1);
    CHECK(replayed == recorded.value.hashes);
    CHECK(report.final_hash == recorded.value.final_hash);
}

TEST_CASE("a recording with an altered hash reports that tick with both hashes", "[replay]") {
    temp_file file("altered_hash");
    session_script script;
    script.alter_hash_at = 180;
    const auto recorded = testing::record_scripted_session(file.path(), script);
    REQUIRE(recorded.ok());

    const replay_report report = replay_file(file.path());
    REQUIRE(report.mismatch.has_value());
    CHECK(report.mismatch->tick == 180);
    CHECK(report.mismatch->actual == recorded.value.hashes[180]);
    CHECK(report.mismatch->expected == (recorded.value.hashes[180] ^ 1));
    CHECK(report.final_tick == 180);  // stopped at the first mismatch
    CHECK_FALSE(report.complete);
}

TEST_CASE("a Hash record follows every tick that is a multiple of the interval", "[replay]") {
    temp_file file("interval_7");
    session_script script;
    script.ticks = 50;
    script.hash_interval = 7;
    REQUIRE(testing::record_scripted_session(file.path(), script).ok());
    const replay_report report = replay_file(file.path());
    CHECK(report.complete);
    CHECK(report.hashes_checked == 1 + 50 / 7 + 1);
}

TEST_CASE("until stops at that tick after checking its hash", "[replay]") {
    temp_file file("until");
    const auto recorded = testing::record_scripted_session(file.path(), {});
    REQUIRE(recorded.ok());
    const replay_report at_120 = replay_file(file.path(), nullptr, 120);
    CHECK(at_120.complete);
    CHECK(at_120.final_tick == 120);
    CHECK(at_120.final_hash == recorded.value.hashes[120]);
    CHECK(at_120.hashes_checked == 3);  // start, 60, 120

    const replay_report at_start = replay_file(file.path(), nullptr, 0);
    CHECK(at_start.complete);
    CHECK(at_start.ticks_replayed == 0);

    const replay_report past_end = replay_file(file.path(), nullptr, 601);
    CHECK_FALSE(past_end.complete);
    CHECK_THAT(past_end.error, Catch::Contains("after the recording's end at tick 600"));
}

TEST_CASE("a recording the server never finished replays to its last tick and is reported as cut short", "[replay]") {
    temp_file file("unfinished");
    session_script script;
    script.finish = false;  // the recorder's destructor flushes what it holds
    REQUIRE(testing::record_scripted_session(file.path(), script).ok());
    const auto size = testing::read_bytes(file.path()).size();
    const replay_report report = replay_file(file.path());
    CHECK(report.ticks_replayed == 600);
    CHECK_FALSE(report.mismatch.has_value());
    CHECK_FALSE(report.complete);
    CHECK_THAT(report.error,
               Catch::Contains("byte offset " + std::to_string(size) + ": the file ends without an End record"));

    // What was replayed is still there for --until, the usual way to look at a crash.
    const replay_report until = replay_file(file.path(), nullptr, 600);
    CHECK(until.complete);
    CHECK(until.error.empty());
}

TEST_CASE("a running recorder has every whole second of ticks on disk", "[replay]") {
    temp_file file("flush_every_second");
    world::world w(world::asteroids_preset(), 5);
    auto opened = recorder::open(file.path(), make_header(w, "asteroids", 5, 30));
    REQUIRE(opened.ok());
    recorder& rec = opened.value;
    const world::body_id player = *w.spawn_player(world::player_id{1});
    for (uint32_t k = 0; k < 75; ++k) {
        match::tick_record record{w.tick(), {}, {}, {{player, {1, 0.5f, 0}}}, {}};
        match::apply_tick(w, record);
        REQUIRE(rec.record_tick(record, w.hash()).ok());
    }
    // 75 ticks at 30 per second: two whole seconds (60 ticks) are on disk, the rest is buffered.
    auto rd = reader::open(file.path());
    REQUIRE(rd.ok());
    uint32_t ticks_on_disk = 0;
    for (;;) {
        auto next = rd.value.next();
        if (!next) {
            CHECK_THAT(next.error, Catch::Contains("without an End record"));
            break;
        }
        if (std::holds_alternative<match::tick_record>(next.value)) ++ticks_on_disk;
    }
    CHECK(ticks_on_disk == 60);
    REQUIRE(rec.finish(w.tick(), w.hash()).ok());
}

TEST_CASE("the recorder refuses a gap in the ticks and a finish at the wrong tick", "[replay]") {
    temp_file file("recorder_gap");
    world::world w(world::asteroids_preset(), 5);
    auto opened = recorder::open(file.path(), make_header(w, "asteroids", 5, 60));
    REQUIRE(opened.ok());
    recorder& rec = opened.value;
    match::tick_record record{w.tick(), {}, {}, {}, {}};
    match::apply_tick(w, record);
    REQUIRE(rec.record_tick(record, w.hash()).ok());
    const auto gap = rec.record_tick(match::tick_record{5, {}, {}, {}, {}}, 0);
    CHECK_THAT(gap.error, Catch::Contains("tick 5 recorded where tick 1 was due"));
    CHECK_THAT(rec.finish(7, 0).error, Catch::Contains("finish at tick 7"));
    REQUIRE(rec.finish(w.tick(), w.hash()).ok());
    CHECK_FALSE(rec.record_tick(record, 0).ok());  // closed
    const replay_report report = replay_file(file.path());
    CHECK(report.complete);
    CHECK(report.ticks_replayed == 1);
}

TEST_CASE("the recorder reports a file it cannot create", "[replay]") {
    world::world w(world::asteroids_preset(), 5);
    auto opened = recorder::open("/nonexistent-dir/x.arpl", make_header(w, "asteroids", 5, 60));
    CHECK_THAT(opened.error, Catch::Contains("/nonexistent-dir/x.arpl: cannot create the replay file"));
}
