// A world config as JSON (Welcome.world_config, the replay header, `arena-sim --config`):
// every field, in a fixed order, so that the same config gives the same bytes and hash.
#include <nlohmann/json.hpp>

#include "server/config/config_json.hpp"
#include "server/config/config_names.hpp"

namespace arena::config {

using nlohmann::json;
using world::vec2;
using namespace names;

namespace {

template <class Enum, size_t N>
const char* enum_name(Enum value, const std::pair<const char*, Enum> (&names)[N]) {
    for (const auto& [text, v] : names)
        if (v == value) return text;
    return "?";
}

json vec_json(const vec2& v) {
    return json::array({v.x(), v.y()});
}

json material_json(const world::body_material& m) {
    return {{"density", m.density},
            {"mass", m.mass},
            {"radius", m.radius},
            {"restitution", m.restitution},
            {"friction", m.friction},
            {"drag_area", m.drag_area},
            {"fixed_rotation", m.fixed_rotation}};
}

json bodies_json(const std::vector<world::body_config>& bodies) {
    json out = json::array();
    for (const world::body_config& b : bodies) {
        json points = json::array();
        for (const vec2& p : b.shape.points) points.push_back(vec_json(p));
        out.push_back({{"shape",
                        {{"type", enum_name(b.shape.type, shape_names)},
                         {"radius", b.shape.radius},
                         {"rounding", b.shape.rounding},
                         {"half_extents", vec_json(b.shape.half_extents)},
                         {"half_length", b.shape.half_length},
                         {"points", points}}},
                       {"material", material_json(b.material)},
                       {"position", vec_json(b.position)},
                       {"angle", b.angle},
                       {"velocity", vec_json(b.velocity)},
                       {"static", b.is_static}});
    }
    return out;
}

}  // namespace

std::string config_to_json(const world::world_config& c) {
    json fluids = json::array();
    for (const auto& f : c.fluids)
        fluids.push_back({{"min", vec_json(f.min)}, {"max", vec_json(f.max)}, {"density", f.density}});
    const auto& k = c.control;
    json j = {
        {"dt", c.dt},
        {"integrator", enum_name(c.integrator, integrator_names)},
        {"gravity", vec_json(c.gravity)},
        {"air_density", c.air_density},
        {"fluids", fluids},
        {"boundary", enum_name(c.boundary, boundary_names)},
        {"size", vec_json(c.size)},
        {"floor_friction", c.floor_friction},
        {"angular_damping", c.angular_damping},
        {"velocity_iterations", c.velocity_iterations},
        {"position_iterations", c.position_iterations},
        {"restitution_threshold", c.restitution_threshold},
        {"penetration_slop", c.penetration_slop},
        {"speculative_distance", c.speculative_distance},
        {"correction_fraction", c.correction_fraction},
        {"max_correction", c.max_correction},
        {"max_bodies", c.max_bodies},
        {"player", material_json(c.player)},
        {"control",
         {{"thrust_force", k.thrust_force},
          {"turn_torque", k.turn_torque},
          {"impulse", k.impulse},
          {"impulse_cooldown_ticks", k.impulse_cooldown_ticks},
          {"thrust_along_facing", k.thrust_along_facing},
          {"impulse_upward", k.impulse_upward},
          {"impulse_needs_ground", k.impulse_needs_ground}}},
        {"rocks",
         {{"count", c.rocks.count},
          {"min_radius", c.rocks.min_radius},
          {"max_radius", c.rocks.max_radius},
          {"max_speed", c.rocks.max_speed},
          {"material", material_json(c.rocks.material)},
          {"polygon_vertices", c.rocks.polygon_vertices}}},
        {"bodies", bodies_json(c.bodies)},
    };
    // Only rules other than the sandbox's: the JSON of a sandbox world (and its hash in
    // Welcome and in recordings) stays what it was before rules existed.
    if (c.rules != "sandbox") j["rules"] = c.rules;
    if (!c.rules_params.empty()) j["rules_params"] = nlohmann::json::parse(c.rules_params);
    // Only sub-stepped worlds name their sub-steps, for the same reason.
    if (c.substeps != 1) j["substeps"] = c.substeps;
    return j.dump(2);
}

}  // namespace arena::config
