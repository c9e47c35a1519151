#pragma once
// Everything that decides a world besides its seed and its inputs. Every field has a default
// and a unit; presets (presets.hpp) and config files (server/config/) start from these.
#include <cstdint>
#include <string>
#include <vector>

#include "server/world/types.hpp"

namespace arena::world {

enum class integrator : uint8_t {
    semi_implicit,   // v += a·dt, then x += v_new·dt (the default: stable, energy-friendly)
    explicit_euler,  // x += v_old·dt, then v += a·dt (the lecture's first method, for comparison)
};

enum class boundary : uint8_t {
    open,   // no bounds
    wrap,   // leaving one side enters the opposite side (Asteroids)
    walls,  // four static walls on [0, size.x] × [0, size.y]; the bottom one is a floor
    floor,  // only the floor y = 0, a static wall of infinite extent
};

// A rectangle of fluid (water, oil) in which drag uses `density` instead of the air's.
struct fluid_region {
    vec2 min{0, 0};          // m, lower-left corner
    vec2 max{0, 0};          // m, upper-right corner
    real density = 1000.0f;  // kg/m³ (water: 1000)
};

// A body's material and shape, used for players and rocks.
struct body_material {
    real density = 1.0f;          // kg/m² (2D: mass = density·area); ignored when mass > 0; a
                                  // shaped body with density 0 and mass 0 is static
    real mass = 0.0f;             // kg; > 0 overrides density
    real radius = 1.0f;           // m, > 0
    real restitution = 0.5f;      // [0, 1]: 0 absorbs an impact, 1 bounces back fully
    real friction = 0.6f;         // μ ≥ 0, Coulomb friction at contacts (Box2D's default)
    real drag_area = 0.0f;        // m², A·Cd: frontal area times drag coefficient
    bool fixed_rotation = false;  // true: never rotates (infinite moment of inertia)
};

// How a player's input becomes forces on its body.
struct control_config {
    real thrust_force = 100.0f;            // N at thrust = 1
    real turn_torque = 50.0f;              // N·m at turn = 1
    real impulse = 20.0f;                  // N·s when button 0 fires
    uint32_t impulse_cooldown_ticks = 30;  // ticks between two impulses
    bool thrust_along_facing = true;       // false: thrust pushes along +x (running, platformer)
    bool impulse_upward = false;           // true: the impulse pushes along +y (a jump)
    bool impulse_needs_ground = false;     // true: the impulse fires only while on the floor
};

// A shape as a config describes it (world.cpp makes the shape.hpp one from it).
enum class shape_type : uint8_t { circle, capsule, box, polygon, segment, chain };

struct shape_config {
    shape_type type = shape_type::circle;
    real radius = 0.5f;             // m > 0: circle and capsule radius
    real rounding = 0.0f;           // m ≥ 0: box and polygon rounding radius
    vec2 half_extents{0.5f, 0.5f};  // m > 0: box
    real half_length = 0.5f;        // m > 0: capsule, whose axis runs along the body's x
    std::vector<vec2> points{};     // m, body frame: polygon (3 to 8, convex hull taken), segment (2),
                                    // chain (2 or more: one static segment per pair)
};

// A body placed when the world is created, before the rocks.
struct body_config {
    shape_config shape{};
    body_material material{};  // its radius is ignored: the shape's counts
    vec2 position{0, 0};       // m
    real angle = 0.0f;         // rad
    vec2 velocity{0, 0};       // m/s
    bool is_static = false;    // never moves (level geometry); segments and chains always are
};

// The non-player bodies spawned from the seed when the world is created.
struct rock_config {
    uint32_t count = 0;
    real min_radius = 1.0f;         // m
    real max_radius = 3.0f;         // m
    real max_speed = 5.0f;          // m/s, each velocity component uniform in [−max, max]
    body_material material{};       // its radius is ignored: drawn in [min_radius, max_radius]
    uint32_t polygon_vertices = 0;  // 0: circles; 3 to 8: irregular convex polygons within the drawn radius
};

struct world_config {
    real dt = 1.0f / 60.0f;  // s, the fixed step
    enum integrator integrator = integrator::semi_implicit;
    vec2 gravity{0, 0};                  // m/s²
    real air_density = 1.2f;             // kg/m³, the medium outside fluid regions
    std::vector<fluid_region> fluids{};  // checked in order; the first containing a body wins
    enum boundary boundary = boundary::open;
    vec2 size{200, 200};                // m, the world is [0, size.x] × [0, size.y]
    real floor_friction = 0.0f;         // μ, kinetic friction of the floor
    real angular_damping = 0.0f;        // 1/s, fraction of ω lost per second
    uint32_t velocity_iterations = 8;   // contact impulse iterations per step
    uint32_t position_iterations = 3;   // penetration correction iterations per step
    real restitution_threshold = 1.0f;  // m/s: slower impacts do not bounce (no jitter at rest)
    real penetration_slop = 0.005f;     // m of overlap left alone (stable resting contact)
    real speculative_distance = 0.02f;  // m: contacts start this far before touching
    real correction_fraction = 0.2f;    // share of the remaining overlap removed per iteration
    real max_correction = 0.2f;         // m, largest positional push per contact per iteration
    uint32_t max_bodies = 1u << 20;     // spawns beyond this fail
    // 1 to 8. 1: the one-step solver (solver.hpp: the iterations, correction_fraction and
    // max_correction above, once per step). More: Box2D v3's soft step (soft_solver.hpp):
    // contacts found once per step, then this many sub-steps of dt/substeps, each integrating,
    // solving soft contacts and relaxing; those fields are not used then, and velocities and
    // positions integrate semi-implicitly whatever `integrator` says.
    uint32_t substeps = 1;
    body_material player{};
    control_config control{};
    rock_config rocks{};
    std::vector<body_config> bodies{};  // placed in order when the world is created
    // The game a match plays this world by, by name (games/registry.hpp); "sandbox" keeps no
    // score. The world ignores it; the match and the replay read it.
    std::string rules = "sandbox";
    // The game's own parameters ("rules_params" in the JSON): an object's text with its keys
    // sorted, "" when absent. The world ignores it; the rules check it and play by it.
    std::string rules_params{};
};

}  // namespace arena::world
