// A stream connection's bounded output (server/net/bounded_output.*): control frames in order up
// to a limit, one snapshot slot that a newer snapshot replaces, and the stall clock.
#include <catch2/catch.hpp>
#include <vector>

#include "server/net/bounded_output.hpp"

using namespace arena;
using namespace arena::net;

namespace {

std::vector<uint8_t> drain_one(bounded_output& out) {
    auto bytes = out.next();
    REQUIRE(bytes);
    return {bytes->begin(), bytes->end()};
}

// Control frames {7} and {8} queued at 11 and 13, around snapshot {1, 1} (at 10) replaced by
// {2, 2} (at 12) before it was written.
void queue_controls_around_a_replaced_snapshot(bounded_output& out) {
    out.put_snapshot_frame(std::vector<uint8_t>{1, 1}, 10);
    CHECK(out.push_control({7}, 11));
    out.put_snapshot_frame(std::vector<uint8_t>{2, 2}, 12);  // replaces the first, never written
    CHECK(out.push_control({8}, 13));
}

}  // namespace

TEST_CASE("control frames go out in order before the snapshot, and only the newest snapshot goes", "[net]") {
    bounded_output out(8);
    queue_controls_around_a_replaced_snapshot(out);
    CHECK(drain_one(out) == std::vector<uint8_t>{7});
    CHECK(drain_one(out) == std::vector<uint8_t>{8});
    CHECK(drain_one(out) == std::vector<uint8_t>{2, 2});
    CHECK_FALSE(out.next());
}

TEST_CASE("control frames beyond the limit are refused, not queued", "[net]") {
    bounded_output out(2);
    CHECK(out.push_control({1}, 0));
    CHECK(out.push_control({2}, 0));
    CHECK_FALSE(out.push_control({3}, 0));
    CHECK(drain_one(out) == std::vector<uint8_t>{1});
    CHECK(drain_one(out) == std::vector<uint8_t>{2});
    CHECK_FALSE(out.next());
    CHECK(out.push_control({4}, 0));  // room again once written
}

TEST_CASE("a last word drops whatever waits", "[net]") {
    bounded_output out(8);
    CHECK(out.push_control({1}, 0));
    out.put_snapshot_frame(std::vector<uint8_t>{9}, 0);
    out.keep_only({5, 5});
    CHECK(drain_one(out) == std::vector<uint8_t>{5, 5});
    CHECK_FALSE(out.next());
}

TEST_CASE("the stall clock runs while output waits unwritten and restarts at each write", "[net]") {
    bounded_output out(8);
    CHECK(out.stalled_ns(100) == 0);
    CHECK(out.push_control({1}, 100));
    CHECK(out.push_control({2}, 150));  // already waiting since 100
    CHECK(out.stalled_ns(400) == 300);
    (void)drain_one(out);
    out.written(500);  // one written, one still waiting: progress at 500
    CHECK(out.stalled_ns(600) == 100);
    (void)drain_one(out);
    out.written(700);  // nothing waits
    CHECK(out.stalled_ns(900) == 0);
    CHECK_FALSE(out.next());
    CHECK(out.stalled_ns(900) == 0);
}

TEST_CASE("take_all gives every waiting frame in order, the snapshot last, for one gathered write", "[net]") {
    bounded_output out(8);
    queue_controls_around_a_replaced_snapshot(out);
    std::vector<std::vector<uint8_t>> frames;
    for (std::span<const uint8_t> frame : out.take_all()) frames.emplace_back(frame.begin(), frame.end());
    CHECK(frames == std::vector<std::vector<uint8_t>>{{7}, {8}, {2, 2}});
    CHECK(out.push_control({9}, 14));  // the limit counts frames waiting, not frames being written
    CHECK(out.stalled_ns(20) == 10);   // nothing written yet: waiting since 10
    out.written(30);
    CHECK(out.stalled_ns(40) == 10);  // {9} still waits: progress at 30
    CHECK(out.take_all().size() == 1);
    out.written(50);
    CHECK(out.take_all().empty());
    CHECK(out.stalled_ns(60) == 0);
}

TEST_CASE("take_all leaves out a close's empty last word and drains", "[net]") {
    bounded_output out(8);
    CHECK(out.push_control({1}, 0));
    out.put_snapshot_frame(std::vector<uint8_t>{9}, 0);
    out.keep_only({});
    CHECK(out.take_all().empty());
    CHECK(out.stalled_ns(100) == 0);
}
