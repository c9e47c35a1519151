#include <catch2/catch.hpp>
#include <limits>

#include "server/world/input.hpp"

using namespace arena::world;

TEST_CASE("non-finite inputs are refused with a reason", "[world][input]") {
    const real nan = std::numeric_limits<real>::quiet_NaN();
    const real inf = std::numeric_limits<real>::infinity();
    CHECK(check_input({nan, 0, 0}).value().find("thrust") != std::string::npos);
    CHECK(check_input({0, inf, 0}).value().find("turn") != std::string::npos);
    CHECK_FALSE(check_input({0.5f, -0.5f, 1}).has_value());
}

TEST_CASE("out-of-range inputs are clamped to [-1, 1]", "[world][input]") {
    const player_input in = clamp_input({5, -7, 3});
    CHECK(in.thrust == 1.0f);
    CHECK(in.turn == -1.0f);
    CHECK(in.buttons == 3);
}
