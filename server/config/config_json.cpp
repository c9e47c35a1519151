#include "server/config/config_json.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "games/registry.hpp"
#include "server/config/config_names.hpp"
#include "server/world/body.hpp"
#include "server/world/presets.hpp"

namespace arena::config {

using nlohmann::json;
using world::real;
using world::vec2;
using namespace names;

namespace {

struct bad_field {
    std::string message;
};

// Reads the fields of one JSON object, and refuses any field it was not asked for.
class object_reader {
public:
    object_reader(const json& j, std::string path) : j_(j), path_(std::move(path)) {
        if (!j_.is_object()) throw bad_field{where() + " must be an object"};
    }

    void read(const char* name, real& out) {
        if (const json* v = take(name)) {
            if (!v->is_number()) throw bad_field{where(name) + " must be a number"};
            const double d = v->get<double>();
            if (!std::isfinite(d) || std::fabs(d) > std::numeric_limits<real>::max())
                throw bad_field{where(name) + " must be a finite number"};
            out = static_cast<real>(d);
        }
    }
    void read(const char* name, uint32_t& out) {
        if (const json* v = take(name)) {
            if (!v->is_number_unsigned() || v->get<uint64_t>() > std::numeric_limits<uint32_t>::max())
                throw bad_field{where(name) + " must be an integer in [0, 4294967295]"};
            out = v->get<uint32_t>();
        }
    }
    void read(const char* name, bool& out) {
        if (const json* v = take(name)) {
            if (!v->is_boolean()) throw bad_field{where(name) + " must be true or false"};
            out = v->get<bool>();
        }
    }
    void read(const char* name, vec2& out) {
        if (const json* v = take(name)) {
            if (!v->is_array() || v->size() != 2 || !(*v)[0].is_number() || !(*v)[1].is_number())
                throw bad_field{where(name) + " must be an array of two numbers [x, y]"};
            json pair = {{"x", (*v)[0]}, {"y", (*v)[1]}};
            object_reader r(pair, where(name));
            r.read("x", out.x());
            r.read("y", out.y());
        }
    }
    template <class Enum, size_t N>
    void read_enum(const char* name, Enum& out, const std::pair<const char*, Enum> (&names)[N]) {
        if (const json* v = take(name)) {
            std::string options;
            for (const auto& [text, value] : names) {
                if (v->is_string() && v->get<std::string>() == text) {
                    out = value;
                    return;
                }
                if (!options.empty()) options.append(", ");
                options.append(text);
            }
            throw bad_field{where(name) + " must be one of: " + options};
        }
    }
    // The sub-object or array `name`, if present.
    const json* take(const char* name) {
        seen_.insert(name);
        auto it = j_.find(name);
        return it == j_.end() ? nullptr : &*it;
    }
    std::string where(const char* name = nullptr) const {
        std::string p = path_;
        if (name) {
            if (!p.empty()) p.append(".");
            p.append(name);
        }
        if (p.empty()) p = "(top level)";
        std::string out = "field '";
        out.append(p).append("'");
        return out;
    }
    std::string child(const char* name) const { return path_.empty() ? name : path_ + "." + name; }
    // Any field not asked for is a typo or a field from another version: refuse it.
    void finish() const {
        for (const auto& [key, value] : j_.items())
            if (!seen_.count(key)) throw bad_field{"unknown " + where(key.c_str())};
    }

private:
    const json& j_;
    std::string path_;
    std::set<std::string> seen_;
};

}  // namespace

bool is_game_name(std::string_view name) {
    if (name.empty() || name.size() > max_game_name || name[0] < 'a' || name[0] > 'z') return false;
    for (const char ch : name)
        if (!((ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '_')) return false;
    return true;
}

namespace {

void read_material(const json& j, const std::string& path, world::body_material& m) {
    object_reader r(j, path);
    r.read("density", m.density);
    r.read("mass", m.mass);
    r.read("radius", m.radius);
    r.read("restitution", m.restitution);
    r.read("friction", m.friction);
    r.read("drag_area", m.drag_area);
    r.read("fixed_rotation", m.fixed_rotation);
    r.finish();
    if (!(m.friction >= 0)) throw bad_field{r.where("friction") + " must not be negative"};
}

void read_points(const json& j, const std::string& path, std::vector<vec2>& points) {
    if (!j.is_array()) throw bad_field{"field '" + path + "' must be an array of [x, y] points"};
    points.clear();
    for (size_t i = 0; i < j.size(); ++i) {
        json holder = {{"p", j[i]}};
        object_reader r(holder, path + "[" + std::to_string(i) + "]");
        vec2 p{0, 0};
        // Named by the point's index: "field 'bodies[0].shape.points[2]' must be ...".
        if (!j[i].is_array() || j[i].size() != 2 || !j[i][0].is_number() || !j[i][1].is_number())
            throw bad_field{"field '" + path + "[" + std::to_string(i) + "]' must be an array of two numbers [x, y]"};
        r.read("p", p);
        points.push_back(p);
    }
}

void read_shape(const json& j, const std::string& path, world::shape_config& s) {
    object_reader r(j, path);
    if (!r.take("type"))
        throw bad_field{r.where("type") + " is required (circle, capsule, box, polygon, segment, chain)"};
    r.read_enum("type", s.type, shape_names);
    r.read("radius", s.radius);
    r.read("rounding", s.rounding);
    r.read("half_extents", s.half_extents);
    r.read("half_length", s.half_length);
    if (const json* p = r.take("points")) read_points(*p, r.child("points"), s.points);
    r.finish();
    if (s.type == world::shape_type::chain) {
        if (s.points.size() < 2) throw bad_field{r.where("points") + " must hold at least two points"};
        for (size_t i = 1; i < s.points.size(); ++i)
            if (s.points[i] == s.points[i - 1])
                throw bad_field{"field '" + r.child("points") + "[" + std::to_string(i) +
                                "]' repeats the point before it (a segment needs two distinct points)"};
        return;
    }
    if (const auto made = world::make_shape(s); !made) {
        const std::string& error = made.error;
        // The shape's message names its field in quotes: make it the full path.
        const size_t quote = error.find('\'');
        const size_t end = quote == std::string::npos ? quote : error.find('\'', quote + 1);
        if (end == std::string::npos) throw bad_field{r.where() + ": " + error};
        const std::string field = error.substr(quote + 1, end - quote - 1);
        throw bad_field{r.where(field.c_str()) + error.substr(end + 1)};
    }
}

void read_bodies(const json& j, const std::string& path, std::vector<world::body_config>& bodies) {
    if (!j.is_array()) throw bad_field{"field '" + path + "' must be an array"};
    bodies.clear();
    for (size_t i = 0; i < j.size(); ++i) {
        world::body_config b;
        const std::string here = path + "[" + std::to_string(i) + "]";
        object_reader r(j[i], here);
        const json* shape = r.take("shape");
        if (!shape) throw bad_field{r.where("shape") + " is required"};
        read_shape(*shape, r.child("shape"), b.shape);
        if (const json* m = r.take("material")) read_material(*m, r.child("material"), b.material);
        r.read("position", b.position);
        r.read("angle", b.angle);
        r.read("velocity", b.velocity);
        r.read("static", b.is_static);
        r.finish();
        bodies.push_back(b);
    }
}

void read_control(const json& j, const std::string& path, world::control_config& c) {
    object_reader r(j, path);
    r.read("thrust_force", c.thrust_force);
    r.read("turn_torque", c.turn_torque);
    r.read("impulse", c.impulse);
    r.read("impulse_cooldown_ticks", c.impulse_cooldown_ticks);
    r.read("thrust_along_facing", c.thrust_along_facing);
    r.read("impulse_upward", c.impulse_upward);
    r.read("impulse_needs_ground", c.impulse_needs_ground);
    r.finish();
}

void read_rocks(const json& j, const std::string& path, world::rock_config& rocks) {
    object_reader r(j, path);
    r.read("count", rocks.count);
    r.read("min_radius", rocks.min_radius);
    r.read("max_radius", rocks.max_radius);
    r.read("max_speed", rocks.max_speed);
    if (const json* m = r.take("material")) read_material(*m, r.child("material"), rocks.material);
    r.read("polygon_vertices", rocks.polygon_vertices);
    r.finish();
    if (rocks.polygon_vertices != 0 && (rocks.polygon_vertices < 3 || rocks.polygon_vertices > 8))
        throw bad_field{r.where("polygon_vertices") + " must be 0 (circles) or 3 to 8"};
}

void read_fluids(const json& j, const std::string& path, std::vector<world::fluid_region>& fluids) {
    if (!j.is_array()) throw bad_field{"field '" + path + "' must be an array"};
    if (j.size() > max_fluid_regions)
        throw bad_field{"field '" + path + "' must hold at most " + std::to_string(max_fluid_regions) +
                        " regions, got " + std::to_string(j.size())};
    fluids.clear();
    for (size_t i = 0; i < j.size(); ++i) {
        world::fluid_region f;
        object_reader r(j[i], path + "[" + std::to_string(i) + "]");
        r.read("min", f.min);
        r.read("max", f.max);
        r.read("density", f.density);
        r.finish();
        fluids.push_back(f);
    }
}

// Values that parse but would break the physics. Every physical field has an interval, wide
// for any game and narrow enough that no product of them overflows a float: a mass of 1e-45
// kg has an inverse of infinity, and NaN followed (it reached the wire). With these bounds a
// body's mass, inertia and their inverses are finite (m ≤ 1e5·π·1e4² ≈ 3e13 kg; I ≥ ½·m·r²
// with m ≥ 3e-9 kg and r ≥ 1e-3 m). The error names the field, its interval and the value.
class range_checker {
public:
    // `value` in [lo, hi] (lo excluded when lo_open).
    void field(const std::string& name, real value, double lo, double hi, const char* unit, bool lo_open = false) {
        // Compared as floats, so that "dt": 0.0001 (9.99999975e-05 as a float) is in [1e-4, 1].
        const double v = value;
        const auto flo = static_cast<real>(lo), fhi = static_cast<real>(hi);
        if ((lo_open ? value > flo : value >= flo) && value <= fhi) return;
        throw bad_field{"field '" + name + "' must be in " + (lo_open ? "(" : "[") + number(lo) + ", " + number(hi) +
                        "]" + (*unit ? " " : "") + unit + ", got " + number(v)};
    }
    void field(const std::string& name, const vec2& value, double lo, double hi, const char* unit) {
        field(name + ".x", value.x(), lo, hi, unit);
        field(name + ".y", value.y(), lo, hi, unit);
    }
    void material(const std::string& path, const world::body_material& m) {
        field(path + ".density", m.density, 0, max_density, "kg/m²");
        // 0 means "from the density"; a positive mass must be one a solver can invert.
        if (m.mass != 0 && !(m.mass >= static_cast<real>(min_mass) && m.mass <= static_cast<real>(max_mass)))
            throw bad_field{"field '" + path + ".mass' must be 0 (from the density) or in [" + number(min_mass) + ", " +
                            number(max_mass) + "] kg, got " + number(m.mass)};
        field(path + ".radius", m.radius, min_radius, max_radius, "m");
        field(path + ".restitution", m.restitution, 0, 1, "");
        field(path + ".drag_area", m.drag_area, 0, max_drag_area, "m²");
    }

    static constexpr double max_density = 1e5;                // kg/m³ (or kg/m² for bodies); osmium is 22 590 kg/m³
    static constexpr double min_mass = 1e-3, max_mass = 1e9;  // kg
    static constexpr double min_radius = 1e-3, max_radius = 1e4;  // m
    static constexpr double max_drag_area = 1e4;                  // m²

private:
    static std::string number(double v) {
        char text[32];
        std::snprintf(text, sizeof text, "%.9g", v);
        return text;
    }
};

void check_ranges(const world::world_config& c) {
    range_checker r;
    r.field("dt", c.dt, 1e-4, 1, "s");
    r.field("gravity", c.gravity, -1000, 1000, "m/s²");
    r.field("air_density", c.air_density, 0, range_checker::max_density, "kg/m³");
    if (c.fluids.size() > max_fluid_regions)
        throw bad_field{"field 'fluids' must hold at most " + std::to_string(max_fluid_regions) + " regions, got " +
                        std::to_string(c.fluids.size())};
    for (size_t i = 0; i < c.fluids.size(); ++i) {
        const std::string at = "fluids[" + std::to_string(i) + "]";
        const world::fluid_region& f = c.fluids[i];
        r.field(at + ".min", f.min, -max_world_size, max_world_size, "m");
        r.field(at + ".max", f.max, -max_world_size, max_world_size, "m");
        if (f.min.x() > f.max.x() || f.min.y() > f.max.y())
            throw bad_field{"field '" + at + "' must have min <= max in both coordinates"};
        r.field(at + ".density", f.density, 0, range_checker::max_density, "kg/m³");
    }
    r.field("size", c.size, 1, max_world_size, "m");
    r.field("floor_friction", c.floor_friction, 0, 100, "");
    r.field("angular_damping", c.angular_damping, 0, 1000, "1/s");
    if (c.velocity_iterations > 100 || c.position_iterations > 100)
        throw bad_field{"solver iterations must be at most 100"};
    if (c.substeps < 1 || c.substeps > max_substeps)
        throw bad_field{"field 'substeps' must be in [1, " + std::to_string(max_substeps) + "], got " +
                        std::to_string(c.substeps)};
    if (c.substeps > 1 && c.integrator != world::integrator::semi_implicit)
        throw bad_field{"field 'substeps' above 1 needs integrator semi-implicit (the sub-steps integrate that way)"};
    r.field("restitution_threshold", c.restitution_threshold, 0, 1e4, "m/s");
    r.field("penetration_slop", c.penetration_slop, 0, 1, "m");
    r.field("speculative_distance", c.speculative_distance, 0, 10, "m");
    r.field("correction_fraction", c.correction_fraction, 0, 1, "");
    r.field("max_correction", c.max_correction, 0, 100, "m");
    if (c.max_bodies > max_world_bodies)
        throw bad_field{"field 'max_bodies' must be at most " + std::to_string(max_world_bodies) + ", got " +
                        std::to_string(c.max_bodies)};
    // Spawn counts: what a config asks the world to create at once. 30 million rocks used to be
    // accepted and spent minutes placing a million of them (a replay's header too) before any
    // check; a count beyond what max_bodies may ever be is refused here, before any work.
    if (c.rocks.count > max_world_bodies)
        throw bad_field{"field 'rocks.count' must be at most " + std::to_string(max_world_bodies) + ", got " +
                        std::to_string(c.rocks.count)};
    if (c.bodies.size() > max_world_bodies)
        throw bad_field{"field 'bodies' must hold at most " + std::to_string(max_world_bodies) + " bodies, got " +
                        std::to_string(c.bodies.size())};
    r.material("player", c.player);
    r.field("control.thrust_force", c.control.thrust_force, 0, 1e7, "N");
    r.field("control.turn_torque", c.control.turn_torque, 0, 1e7, "N·m");
    r.field("control.impulse", c.control.impulse, 0, 1e7, "N·s");
    r.field("rocks.min_radius", c.rocks.min_radius, range_checker::min_radius, range_checker::max_radius, "m");
    r.field("rocks.max_radius", c.rocks.max_radius, c.rocks.min_radius, range_checker::max_radius, "m");
    r.field("rocks.max_speed", c.rocks.max_speed, 0, 1e4, "m/s");
    r.material("rocks.material", c.rocks.material);
}

world::world_config read_world(const json& j) {
    object_reader r(j, "");
    world::world_config c;
    if (const json* preset = r.take("preset")) {
        if (!preset->is_string()) throw bad_field{"field 'preset' must be a string"};
        auto p = games::scene_by_name(preset->get<std::string>());
        if (!p)
            throw bad_field{"field 'preset': unknown preset '" + preset->get<std::string>() + "' (" +
                            games::scene_names_list() + ")"};
        c = *p;
    }
    r.read("dt", c.dt);
    r.read_enum("integrator", c.integrator, integrator_names);
    r.read("gravity", c.gravity);
    r.read("air_density", c.air_density);
    if (const json* f = r.take("fluids")) read_fluids(*f, "fluids", c.fluids);
    r.read_enum("boundary", c.boundary, boundary_names);
    r.read("size", c.size);
    r.read("floor_friction", c.floor_friction);
    r.read("angular_damping", c.angular_damping);
    r.read("velocity_iterations", c.velocity_iterations);
    r.read("position_iterations", c.position_iterations);
    r.read("substeps", c.substeps);
    r.read("restitution_threshold", c.restitution_threshold);
    r.read("penetration_slop", c.penetration_slop);
    r.read("speculative_distance", c.speculative_distance);
    r.read("correction_fraction", c.correction_fraction);
    r.read("max_correction", c.max_correction);
    r.read("max_bodies", c.max_bodies);
    if (const json* m = r.take("player")) read_material(*m, "player", c.player);
    if (const json* m = r.take("control")) read_control(*m, "control", c.control);
    if (const json* m = r.take("rocks")) read_rocks(*m, "rocks", c.rocks);
    if (const json* b = r.take("bodies")) read_bodies(*b, "bodies", c.bodies);
    // Any well-formed name: whether this build has the game is the registry's to say
    // (games/registry.hpp), so that a client built before a game still reads its worlds.
    if (const json* g = r.take("rules")) {
        if (!g->is_string() || !is_game_name(g->get<std::string>()))
            throw bad_field{r.where("rules") + " must be a game's name: a lower case letter, then up to " +
                            std::to_string(max_game_name - 1) + " lower case letters, digits or _"};
        c.rules = g->get<std::string>();
    }
    if (const json* p = r.take("rules_params")) {
        if (!p->is_object()) throw bad_field{r.where("rules_params") + " must be an object"};
        c.rules_params = p->dump();  // keys sorted: one text, one hash, for equal parameters
    }
    r.finish();
    check_ranges(c);
    return c;
}

}  // namespace

result<world::world_config> parse_config_json(std::string_view text) {
    using config_result = result<world::world_config>;
    if (text.size() > max_config_bytes)
        return config_result::failure("config of " + std::to_string(text.size()) + " bytes; at most " +
                                      std::to_string(max_config_bytes) + " are read");
    json j;
    try {
        j = json::parse(text);
    } catch (const json::exception& e) {
        // parse_error for bad syntax, out_of_range for a number too large to represent (found
        // by fuzz_config; kept in tests/fuzz/regressions/fuzz_config/).
        return config_result::failure(std::string("invalid JSON: ") + e.what());
    }
    try {
        return config_result::success(read_world(j));
    } catch (const bad_field& e) {
        return config_result::failure(e.message);
    } catch (const json::exception& e) {
        return config_result::failure(std::string("invalid config: ") + e.what());
    }
}

result<world::world_config> load_config_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return result<world::world_config>::failure(path + ": cannot open");
    std::ostringstream text;
    text << in.rdbuf();
    auto parsed = parse_config_json(text.str());
    if (!parsed) parsed.error = path + ": " + parsed.error;
    return parsed;
}

}  // namespace arena::config
