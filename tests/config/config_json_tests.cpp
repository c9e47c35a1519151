#include <catch2/catch.hpp>
#include <variant>

#include "server/config/config_json.hpp"
#include "server/world/hash.hpp"
#include "server/world/presets.hpp"

using namespace arena;

namespace {

std::string error_of(std::string_view text) {
    auto r = config::parse_config_json(text);
    REQUIRE(!r.ok());
    return r.error;
}

}  // namespace

TEST_CASE("a config survives JSON bit for bit", "[config]") {
    for (const auto& preset : {world::asteroids_preset(), world::platformer_preset()}) {
        auto back = config::parse_config_json(config::config_to_json(preset));
        REQUIRE(back.ok());
        CHECK(world::config_hash(back.value) == world::config_hash(preset));
    }
}

TEST_CASE("a config file starts from a preset and overrides fields", "[config]") {
    auto r = config::parse_config_json(R"({"preset": "platformer", "gravity": [0, -3.5], "rocks": {"count": 2}})");
    REQUIRE(r.ok());
    const auto& c = r.value;
    CHECK(c.gravity.y() == -3.5f);
    CHECK(c.rocks.count == 2);
    CHECK(c.boundary == world::boundary::walls);  // from the preset
}

TEST_CASE("a wrong field is named in the error", "[config]") {
    CHECK(error_of(R"({"gravty": [0, 1]})").find("'gravty'") != std::string::npos);
    CHECK(error_of(R"({"rocks": {"cout": 3}})").find("'rocks.cout'") != std::string::npos);
    CHECK(error_of(R"({"dt": "fast"})").find("'dt' must be a number") != std::string::npos);
    CHECK(error_of(R"({"gravity": [0]})").find("'gravity'") != std::string::npos);
    CHECK(error_of(R"({"boundary": "donut"})").find("one of: open, wrap, walls, floor") != std::string::npos);
    CHECK(error_of(R"({"preset": "tetris"})").find("unknown preset 'tetris'") != std::string::npos);
    CHECK(error_of(R"({"dt": 0})").find("'dt'") != std::string::npos);
    CHECK(error_of(R"({"fluids": [{"min": [0, 0], "max": [1, 1], "densty": 3}]})").find("'fluids[0].densty'") !=
          std::string::npos);
    CHECK(error_of("{ not json").find("invalid JSON") != std::string::npos);
    // A chain's repeated point would make a segment of no length, whose normal is NaN.
    CHECK(error_of(R"({"bodies": [{"shape": {"type": "chain", "points": [[0, 0], [1, 0], [1, 0]]}}]})")
              .find("'bodies[0].shape.points[2]' repeats the point before it") != std::string::npos);
    // Regression (fuzz_config): a number too large for a double threw out_of_range, which
    // escaped the parser and ended the process.
    CHECK(error_of(R"({"rocks": 1111111111111111111111e1111111111111111111})").find("invalid JSON") !=
          std::string::npos);
}

TEST_CASE("a missing config file is reported with its path", "[config]") {
    auto r = config::load_config_file("/nonexistent/arena.json");
    REQUIRE(!r.ok());
    CHECK(r.error.find("/nonexistent/arena.json") != std::string::npos);
}

TEST_CASE("substeps: read, checked, and written only when not 1", "[config][substeps]") {
    auto r = config::parse_config_json(R"({"substeps": 4})");
    REQUIRE(r.ok());
    const auto& c = r.value;
    CHECK(c.substeps == 4);
    // A sub-stepped config survives JSON, and its hash is not the one-step config's.
    auto back = config::parse_config_json(config::config_to_json(c));
    REQUIRE(back.ok());
    CHECK(back.value.substeps == 4);
    CHECK(world::config_hash(back.value) == world::config_hash(c));
    CHECK(world::config_hash(c) != world::config_hash(world::world_config{}));
    // The pyramid preset sub-steps, and survives JSON too.
    auto pyramid = config::parse_config_json(R"({"preset": "pyramid"})");
    REQUIRE(pyramid.ok());
    CHECK(pyramid.value.substeps == 4);
    // A one-step config's JSON does not name the field: its text and its hash in Welcome and
    // in recordings stay what they were before sub-steps existed.
    CHECK(config::config_to_json(world::world_config{}).find("substeps") == std::string::npos);
    CHECK(error_of(R"({"substeps": 0})") == "field 'substeps' must be in [1, 8], got 0");
    CHECK(error_of(R"({"substeps": 9})") == "field 'substeps' must be in [1, 8], got 9");
    CHECK(error_of(R"({"substeps": -1})").find("'substeps'") != std::string::npos);
    CHECK(error_of(R"({"substeps": 2, "integrator": "explicit"})").find("'substeps'") != std::string::npos);
}
