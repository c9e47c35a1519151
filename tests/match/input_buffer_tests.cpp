#include <catch2/catch.hpp>

#include "server/match/input_buffer.hpp"

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
