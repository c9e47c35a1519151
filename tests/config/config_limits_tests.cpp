// Every physical field of a config has an interval (server/config/config_json.cpp), and a
// config's JSON always fits the Welcome that carries it.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <variant>

#include "protocol/messages.hpp"
#include "protocol/version.hpp"
#include "server/config/config_json.hpp"
#include "server/world/world.hpp"

using namespace arena;

namespace {

std::string error_of(const std::string& text) {
    auto r = config::parse_config_json(text);
    REQUIRE(!r.ok());
    return r.error;
}

world::world_config parsed(const std::string& text) {
    auto r = config::parse_config_json(text);
    if (!r) FAIL(r.error);
    return r.value;
}

bool all_finite(const world::world& w) {
    for (const world::body& b : w.bodies()) {
        for (float v : {b.position.x(), b.position.y(), b.velocity.x(), b.velocity.y(), b.angle, b.angular_velocity,
                        b.mass, b.inv_mass, b.inertia, b.inv_inertia})
            if (!std::isfinite(v)) return false;
    }
    return true;
}

}  // namespace

TEST_CASE("config values that broke the physics are refused, naming the field", "[config][limits]") {
    // Each of these was accepted; the first put NaN on the wire.
    CHECK(error_of(R"({"player": {"mass": 1e-45}})") ==
          "field 'player.mass' must be 0 (from the density) or in [0.001, 1e+09] kg, got 1.40129846e-45");
    CHECK(error_of(R"({"rocks": {"material": {"mass": 1e-45}}})").find("'rocks.material.mass'") != std::string::npos);
    CHECK(error_of(R"({"player": {"restitution": -0.5}})") == "field 'player.restitution' must be in [0, 1], got -0.5");
    CHECK(error_of(R"({"player": {"density": -1}})") == "field 'player.density' must be in [0, 100000] kg/m², got -1");
    CHECK(error_of(R"({"dt": 1e-45})") == "field 'dt' must be in [0.0001, 1] s, got 1.40129846e-45");
    CHECK(error_of(R"({"player": {"radius": 3e38}})") ==
          "field 'player.radius' must be in [0.001, 10000] m, got 3.00000001e+38");
    CHECK(error_of(R"({"rocks": {"max_radius": 3e38}})").find("'rocks.max_radius'") != std::string::npos);
    CHECK(error_of(R"({"gravity": [0, -1e30]})") ==
          "field 'gravity.y' must be in [-1000, 1000] m/s², got -1.00000002e+30");
    CHECK(error_of(R"({"angular_damping": -1})").find("'angular_damping'") != std::string::npos);
    CHECK(error_of(R"({"correction_fraction": 2})").find("'correction_fraction'") != std::string::npos);
    CHECK(error_of(R"({"control": {"thrust_force": 1e20}})").find("'control.thrust_force'") != std::string::npos);
    CHECK(error_of(R"({"size": [0.5, 100]})").find("'size.x'") != std::string::npos);
    CHECK(error_of(R"({"max_bodies": 2000000})") == "field 'max_bodies' must be at most 1048576, got 2000000");
    CHECK(error_of(R"({"fluids": [{"min": [5, 0], "max": [1, 1]}]})") ==
          "field 'fluids[0]' must have min <= max in both coordinates");
    CHECK(error_of(R"({"fluids": [{"min": [0, 0], "max": [1, 1], "density": -3}]})").find("'fluids[0].density'") !=
          std::string::npos);
}

TEST_CASE("a config's size is bounded: fluid regions, then the text itself", "[config][limits]") {
    std::string fluids = R"({"fluids": [)";
    for (size_t i = 0; i <= config::max_fluid_regions; ++i) fluids += std::string(i ? "," : "") + "{}";
    CHECK(error_of(fluids + "]}") == "field 'fluids' must hold at most 256 regions, got 257");
    // 400 000 regions made a 54 MB Welcome; now the text is refused before it is parsed.
    std::string many = R"({"fluids": [)";
    for (int i = 0; i < 400000; ++i) many += std::string(i ? "," : "") + "{}";
    CHECK(error_of(many + "]}").find("at most 1048576 are read") != std::string::npos);
}

TEST_CASE("the largest config there can be still fits a Welcome", "[config][limits]") {
    // Every field at a value with the longest text a float can have, 256 fluid regions.
    world::world_config c;
    const float ugly = -1.17549435e-38f * 1e30f;  // nine significant digits, an exponent, a sign
    c.gravity = {ugly, ugly};
    for (size_t i = 0; i < config::max_fluid_regions; ++i)
        c.fluids.push_back({{-123456.789f, -123456.789f}, {ugly, ugly}, 12345.6789f});
    const std::string text = config::config_to_json(c);
    CHECK(text.size() < 64 * 1024);
    protocol::welcome_info w;
    w.preset = std::string(64, 'p');
    w.world_config = text;
    CHECK(protocol::encode_welcome(w).size() <= protocol::max_server_frame_body);
    static_assert(config::max_config_bytes < protocol::max_server_frame_body);
}

TEST_CASE("max_bodies limits the rocks a config spawns", "[config][limits]") {
    const world::world w(parsed(R"({"max_bodies": 10, "rocks": {"count": 100}})"), 1);
    CHECK(w.bodies().size() == 10);
}

TEST_CASE("a spawn count beyond what max_bodies may be is refused at load, naming the field", "[config][limits]") {
    // 30 million rocks were accepted, and the world then placed a million of them (minutes).
    CHECK(error_of(R"({"preset": "asteroids", "rocks": {"count": 30000000}})") ==
          "field 'rocks.count' must be at most 1048576, got 30000000");
    CHECK(error_of(R"({"rocks": {"count": 1048577}})") == "field 'rocks.count' must be at most 1048576, got 1048577");
    // The limit itself is a valid count (max_bodies then stops the spawning, as above).
    CHECK(parsed(R"({"rocks": {"count": 1048576}, "max_bodies": 10})").rocks.count == 1048576);
}

TEST_CASE("each field at either end of its interval leaves a preset's world finite", "[config][limits]") {
    // One field at a time, from each preset, with players at full thrust, turn and impulse.
    // (Every field at its extreme at once can still diverge: a 1 g, 1 mm body under 1e7 N·m
    // spins at 1e19 rad/s within seconds. The wire is guarded against that separately.)
    const char* fields[] = {
        R"("dt": 0.0001)",
        R"("dt": 1)",
        R"("gravity": [1000, -1000])",
        R"("air_density": 100000)",
        R"("size": [1, 1])",
        R"("size": [1000000, 1000000])",
        R"("floor_friction": 100)",
        R"("angular_damping": 1000)",
        R"("restitution_threshold": 10000)",
        R"("penetration_slop": 1, "speculative_distance": 10, "max_correction": 100, "correction_fraction": 1)",
        R"("player": {"mass": 0.001})",
        R"("player": {"mass": 1e9})",
        R"("player": {"radius": 0.001})",
        R"("player": {"radius": 10000})",
        R"("player": {"density": 100000, "mass": 0, "radius": 10000})",
        R"("player": {"restitution": 1, "drag_area": 10000})",
        R"("control": {"thrust_force": 1e7, "turn_torque": 1e7, "impulse": 1e7, "impulse_cooldown_ticks": 0})",
        R"("rocks": {"count": 50, "min_radius": 0.001, "max_radius": 0.001, "max_speed": 10000})",
        R"("rocks": {"count": 50, "min_radius": 10000, "max_radius": 10000})",
        R"("rocks": {"count": 50, "material": {"density": 100000, "restitution": 1, "drag_area": 10000}})",
        R"("fluids": [{"min": [-1000000, -1000000], "max": [1000000, 1000000], "density": 100000}])",
        R"("substeps": 2)",
        R"("substeps": 8)",
    };
    for (const char* preset : {"asteroids", "platformer"}) {
        for (const char* field : fields) {
            INFO(preset << ": " << field);
            world::world w(parsed(std::string(R"({"preset": ")") + preset + "\", " + field + "}"), 1);
            world::tick_inputs inputs;
            for (uint32_t owner = 1; owner <= 4; ++owner)
                inputs.push_back({*w.spawn_player(world::player_id{owner}), {1.0f, 1.0f, 1}});
            for (int k = 0; k < 600; ++k) w.step(inputs);
            CHECK(all_finite(w));
        }
    }
}
