#include <catch2/catch.hpp>

#include "server/match/input_buffer.hpp"

#include <deque>

using namespace arena::match;

TEST_CASE("each tick consumes one input in order", "[match][input]") {
    input_buffer buffer(4);
    buffer.push({1, {0.1f, 0, 0}});
    buffer.push({2, {0.2f, 0, 0}});
    CHECK(buffer.consume().thrust == 0.1f);
    CHECK(buffer.last_consumed_sequence() == 1);
    CHECK(buffer.consume().thrust == 0.2f);
    CHECK(buffer.last_consumed_sequence() == 2);
}

TEST_CASE("an empty buffer repeats the last input and counts an underrun", "[match][input]") {
    input_buffer buffer(4);
    buffer.push({7, {0.5f, -0.5f, 1}});
    buffer.consume();
    const auto repeated = buffer.consume();
    CHECK(repeated.thrust == 0.5f);
    CHECK(repeated.turn == -0.5f);
    CHECK(buffer.last_consumed_sequence() == 7);
    CHECK(buffer.underruns() == 1);
}

TEST_CASE("a full buffer drops its oldest input and counts an overflow", "[match][input]") {
    input_buffer buffer(2);
    for (uint32_t s = 1; s <= 5; ++s) buffer.push({s, {}});
    CHECK(buffer.overflows() == 3);
    buffer.consume();
    CHECK(buffer.last_consumed_sequence() == 4);
}

TEST_CASE("the ring keeps order across many laps of pushes and consumes", "[match][input]") {
    // Against a plain queue: capacity 3, pushes and consumes in an irregular pattern, so the
    // oldest input sits at every slot of the ring, with overflows and underruns on the way.
    input_buffer buffer(3);
    std::deque<uint32_t> model;
    uint64_t overflows = 0, underruns = 0;
    uint32_t last = 0, next = 1;
    bool consumed_any = false;
    for (int step = 0; step < 500; ++step) {
        const int pushes = (step * 7) % 5;  // 0 to 4 a step: sometimes more than the ring holds
        for (int k = 0; k < pushes; ++k) {
            buffer.push({next, {}});
            if (model.size() == 3) {
                model.pop_front();
                ++overflows;
            }
            model.push_back(next++);
        }
        REQUIRE(buffer.waiting() == model.size());
        const int consumes = (step * 3) % 4;
        for (int k = 0; k < consumes; ++k) {
            buffer.consume();
            if (model.empty()) {
                if (consumed_any) ++underruns;
            } else {
                last = model.front();
                model.pop_front();
                consumed_any = true;
            }
            REQUIRE(buffer.last_consumed_sequence() == last);
        }
    }
    CHECK(buffer.overflows() == overflows);
    CHECK(buffer.underruns() == underruns);
    CHECK(overflows > 0);
    CHECK(underruns > 0);
}
