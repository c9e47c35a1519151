// arena-bench-pyramids: Box2D's pyramid benchmarks, our world against Box2D 2.4.1 (Debian
// libbox2d-dev) in the same process, the engines alternating run by run, so that both see the
// same state of this shared machine.
//
//   pyramid         one pyramid of base 20 (210 boxes)
//   large_pyramid   one pyramid of base 100 (5 050 boxes), Box2D v3's benchmark of that name
//   many_pyramids   20 rows × 20 columns of pyramids of base 10 (22 000 boxes), a ground segment
//                   under each row, Box2D v3's benchmark of that name
//
// The scenes are built as Box2D v3's shared/benchmarks.c builds them: 1 m boxes (density 1,
// friction 0.6, no restitution) placed exactly touching each other and the ground (large_pyramid:
// ground top at y = 0, across ±100 m; many_pyramids: rows 11 m apart, pyramids 11 m apart on
// 220 m segments). The steps are those of v3's benchmark/main.c: gravity −10 m/s², Δt = 1/60 s
// with 4 sub-steps, 500 steps (many_pyramids: 200), the first one untimed.
//
// How each engine sub-steps differs, and is what the comparison measures. Ours steps 1/60 s in
// 4 sub-steps inside the step (world_config::substeps = 4, server/world/soft_solver.hpp, v3's
// soft step): one collision pass per step, then per sub-step two soft passes and one relax pass.
// Box2D 2.4.1 has no sub-steps, so its sub-step is a whole step of 1/240 s with 8 velocity and
// 3 position iterations (Step(dt/4, 8, 3)): 4 collision passes and 4 × 11 solver passes per
// 1/60 s. Both are timed per 1/60 s of simulated time and both must leave every pyramid
// standing. At Δt = 1/60 without sub-steps a 100-level stack does not converge in 8 iterations
// in either one-step solver: both pyramids shake apart (tops 1–2 m off after 250 steps, boxes
// at up to 2.8 m/s).
//
// Box2D 2.4 wraps every polygon and edge in a skin of b2_polygonRadius (1 cm): SetAsBox(0.5)
// collides as a 1.02 m box, and boxes placed 1 m apart start 2 cm inside each other; 100
// levels of that push the large pyramid up and apart (its top rose 0.54 m and slid 0.35 m).
// So Box2D's boxes are SetAsBox(0.5 − skin), 1 m boxes for collision, with the density that
// makes them 1 kg as ours, and its ground edges sit a skin below the ground line.
//
// Sleeping is off in Box2D (as in v3's benchmarks; ours has none): the figures compare the
// work of a step, not of a step skipped. Time is the thread's CPU time per step of 1/60 s
// (the machine is shared: wall time counts other people's work too), best of the runs. A
// pyramid stands when every one of its boxes ends within half a box (0.5 m) of where it
// started: a settled pyramid sinks a little (Box2D 2.4.1 by about its slop per level; ours
// because a soft contact gives under the weight above it, about 0.2 m at the top of the large
// pyramid), a box that fell moves by a box or more.
//
// usage: arena-bench-pyramids [--quick] [--only pyramid,large_pyramid,many_pyramids]
#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "server/world/world.hpp"

using namespace arena;

namespace {

constexpr float half_size = 0.5f;  // m, half the side of a box
constexpr int sub_steps = 4;       // per step of 1/60 s, as Box2D v3's benchmarks (ours: inside the step)
constexpr float step_dt = 1.0f / 60.0f;
constexpr float standing_tolerance = 0.5f;  // m: half a box

struct box_at {
    float x, y;
};

struct ground_line {
    float x0, x1, y;  // m
};

struct scene {
    std::string name;
    std::vector<box_at> boxes;
    std::vector<ground_line> grounds;
    std::vector<size_t> first_box;  // each pyramid's first box; its last box is its top
    int steps = 0;
};

// A pyramid of `base` boxes in its bottom row, whose first box is centred at (x0, y0 + ½).
void add_pyramid(scene& s, int base, float x0, float y0) {
    s.first_box.push_back(s.boxes.size());
    for (int i = 0; i < base; ++i)
        for (int j = i; j < base; ++j)
            s.boxes.push_back({x0 + static_cast<float>(i) * half_size + static_cast<float>(j - i) * 2 * half_size,
                               y0 + half_size + static_cast<float>(i) * 2 * half_size});
}

scene make_scene(const std::string& name, bool quick) {
    scene s;
    s.name = name;
    if (name == "pyramid" || name == "large_pyramid") {
        const int base = name == "pyramid" ? 20 : 100;
        add_pyramid(s, base, half_size - half_size * static_cast<float>(base), 0);
        s.grounds.push_back({-100, 100, 0});
        s.steps = quick ? 50 : 500;
    } else {
        const int base = 10, rows = 20, columns = 20;
        const float ground_gap = 2 * half_size * (base + 1);               // 11 m between rows
        const float ground_width = ground_gap * columns;                   // 220 m
        const float pyramid_pitch = 2 * half_size * base + 2 * half_size;  // 11 m between pyramids
        for (int row = 0; row < rows; ++row) {
            const float y = ground_gap * static_cast<float>(row);
            s.grounds.push_back({-0.5f * ground_width, 0.5f * ground_width, y});
            for (int col = 0; col < columns; ++col)
                add_pyramid(s, base, -0.5f * ground_width + static_cast<float>(col) * pyramid_pitch + 2 * half_size, y);
        }
        s.steps = quick ? 20 : 200;
    }
    s.first_box.push_back(s.boxes.size());
    return s;
}

double thread_cpu_ms() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

struct scene_result {
    double best_ms = 1e300;  // CPU ms per step of 1/60 s, best run
    size_t pyramids = 0;
    size_t standing = 0;        // pyramids standing at the end of the last run
    float worst_top_drift = 0;  // m, the farthest any pyramid's top box ended from its start
    float worst_box_drift = 0;  // m, the farthest any box ended from its start
};

// Every box's end position, in the scene's order: which pyramids stand (see the header).
void check_standing(const scene& s, const std::vector<box_at>& end, scene_result& r) {
    r.pyramids = s.first_box.size() - 1;
    r.standing = 0;
    for (size_t p = 0; p + 1 < s.first_box.size(); ++p) {
        float worst = 0;
        for (size_t i = s.first_box[p]; i < s.first_box[p + 1]; ++i)
            worst = std::max(worst, std::hypot(end[i].x - s.boxes[i].x, end[i].y - s.boxes[i].y));
        const size_t top = s.first_box[p + 1] - 1;
        r.worst_top_drift =
            std::max(r.worst_top_drift, std::hypot(end[top].x - s.boxes[top].x, end[top].y - s.boxes[top].y));
        r.worst_box_drift = std::max(r.worst_box_drift, worst);
        if (worst <= standing_tolerance) ++r.standing;
    }
}

// `step` once untimed (both engines create their contacts in the first step), then the rest timed.
template <class Step>
void time_steps(const scene& s, scene_result& r, Step step) {
    step();
    const double t0 = thread_cpu_ms();
    for (int k = 1; k < s.steps; ++k) step();
    r.best_ms = std::min(r.best_ms, (thread_cpu_ms() - t0) / (s.steps - 1));
}

void run_arena(const scene& s, scene_result& r) {
    world::world_config c;
    c.dt = step_dt;
    c.substeps = sub_steps;
    c.gravity = {0, -10};
    c.air_density = 0;
    c.boundary = world::boundary::open;
    c.max_bodies = static_cast<uint32_t>(s.boxes.size() + s.grounds.size() + 16);
    c.rocks.count = 0;
    world::world w(c, 1);
    const world::body_material ground;
    for (const ground_line& g : s.grounds) w.add_chain(std::vector<world::vec2>{{g.x0, g.y}, {g.x1, g.y}}, ground);
    world::body_material m;
    m.density = 1;
    m.friction = 0.6f;
    m.restitution = 0;
    const world::shape box = world::make_box(half_size, half_size);
    std::vector<uint32_t> ids;
    for (const box_at& b : s.boxes) ids.push_back(*w.add_body(world::make_body(m, box, {b.x, b.y}), box));
    time_steps(s, r, [&] { w.step({}); });
    std::vector<box_at> end;
    for (uint32_t id : ids) {
        const world::body& b = *w.find(id);
        end.push_back({b.position.x(), b.position.y()});
    }
    check_standing(s, end, r);
}

void run_box2d(const scene& s, scene_result& r) {
    b2World w(b2Vec2(0, -10));
    w.SetAllowSleeping(false);
    b2BodyDef ground_def;
    b2Body* ground = w.CreateBody(&ground_def);
    for (const ground_line& g : s.grounds) {
        b2EdgeShape edge;  // its skin's top on the ground line
        edge.SetTwoSided(b2Vec2(g.x0, g.y - b2_polygonRadius), b2Vec2(g.x1, g.y - b2_polygonRadius));
        ground->CreateFixture(&edge, 0);
    }
    const float core = half_size - b2_polygonRadius;
    b2PolygonShape box;
    box.SetAsBox(core, core);
    b2FixtureDef fixture;
    fixture.shape = &box;
    fixture.density = 1.0f / (4 * core * core);  // 1 kg, as ours (Box2D's mass ignores the skin)
    fixture.friction = 0.6f;
    std::vector<b2Body*> bodies;
    for (const box_at& b : s.boxes) {
        b2BodyDef def;
        def.type = b2_dynamicBody;
        def.position.Set(b.x, b.y);
        b2Body* body = w.CreateBody(&def);
        body->CreateFixture(&fixture);
        bodies.push_back(body);
    }
    time_steps(s, r, [&] {
        for (int k = 0; k < sub_steps; ++k) w.Step(step_dt / sub_steps, 8, 3);
    });
    std::vector<box_at> end;
    for (const b2Body* b : bodies) end.push_back({b->GetPosition().x, b->GetPosition().y});
    check_standing(s, end, r);
}

}  // namespace

int main(int argc, char** argv) {
    bool quick = false;
    std::string only = "pyramid,large_pyramid,many_pyramids";
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--quick")) {
            quick = true;
        } else if (!std::strcmp(argv[i], "--only") && i + 1 < argc) {
            only = argv[++i];
        } else {
            std::fprintf(stderr,
                         "usage: arena-bench-pyramids [--quick] [--only pyramid,large_pyramid,many_pyramids]\n");
            return 2;
        }
    }
    const std::string listed = "," + only + ",";
    for (const char* name : {"pyramid", "large_pyramid", "many_pyramids"}) {
        if (listed.find(std::string(",") + name + ",") == std::string::npos) continue;
        const scene s = make_scene(name, quick);
        // many_pyramids takes a minute a run in each engine: one run.
        const int runs = quick || s.boxes.size() > 10000 ? 1 : 2;
        scene_result arena_r, box2d_r;
        for (int k = 0; k < runs; ++k) {
            run_arena(s, arena_r);
            run_box2d(s, box2d_r);
        }
        for (const auto& [engine, r] : {std::pair{"arena", arena_r}, std::pair{"box2d-2.4.1", box2d_r}}) {
            std::printf(
                "{\"bench\":\"pyramids\",\"scene\":\"%s\",\"engine\":\"%s\",\"boxes\":%zu,\"steps\":%d,\"runs\":%d,"
                "\"cpu_ms_per_step\":%.4f,\"standing\":%s,\"worst_top_drift_m\":%.4f,\"sub_steps\":%d,"
                "\"pyramids\":%zu,\"pyramids_standing\":%zu,\"worst_box_drift_m\":%.4f}\n",
                name, engine, s.boxes.size(), s.steps, runs, r.best_ms, r.standing == r.pyramids ? "true" : "false",
                static_cast<double>(r.worst_top_drift), sub_steps, r.pyramids, r.standing,
                static_cast<double>(r.worst_box_drift));
        }
        std::fflush(stdout);
    }
    return 0;
}
