// arena-bench-pyramids: Box2D's pyramid benchmarks, our world against Box2D 2.4.1 (Debian
// libbox2d-dev) in the same process, the engines alternating run by run, so that both see the
// same state of this shared machine. Each run first steps `warmup` times untimed (both engines
// create their contacts in the first steps).
//
//   pyramid         one pyramid of base 20 (210 boxes)
//   large_pyramid   one pyramid of base 100 (5 050 boxes), Box2D's scene of that name
//   many_pyramids   20 × 20 pyramids of base 10 (22 000 boxes) on 20 grounds, after Box2D's
//
// The same scenes in both engines: 1 m boxes (density 1, friction 0.6, no restitution) resting
// exactly on each other and on a static ground, gravity −10 m/s², Δt = 1/60 s, 8 velocity and
// 3 position iterations (Box2D 2.4's Step(dt, 8, 3), which our world also runs). Sleeping is off
// in Box2D (ours has none): the figures compare the work of a step, not of a step skipped.
// Time is the thread's CPU time per step (the machine is shared: wall time counts other
// people's work too), best of the runs (2). At the end each pyramid's top box must be within 25 cm
// of its start across and at 90 % of its height or more, in both engines, or the row says it
// fell: a tall pyramid settles by about the slop per level (0.5 m at base 100, in both engines),
// a fallen one loses metres.
//
// usage: arena-bench-pyramids [--quick]     prints one JSON line per engine and scene
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

struct box_at {
    float x, y;
};

struct scene {
    std::string name;
    std::vector<box_at> boxes;
    std::vector<std::pair<float, float>> grounds;  // segment x range, at y = 0... per pyramid row
    std::vector<float> ground_y;
    std::vector<size_t> tops;  // index of each pyramid's top box
    int warmup = 0;
    int steps = 0;
};

void add_pyramid(scene& s, int base, float cx, float y0) {
    for (int i = 0; i < base; ++i)
        for (int j = i; j < base; ++j) {
            const float x =
                static_cast<float>(i) * 0.5f + static_cast<float>(j - i) - 0.5f * static_cast<float>(base) + 0.5f;
            s.boxes.push_back({cx + x, y0 + 0.5f + static_cast<float>(i)});
        }
    s.tops.push_back(s.boxes.size() - 1);
}

scene make_scene(const std::string& name, bool quick) {
    scene s;
    s.name = name;
    if (name == "pyramid") {
        add_pyramid(s, 20, 0, 0);
        s.grounds.push_back({-40, 40});
        s.ground_y.push_back(0);
        s.warmup = 60;
        s.steps = quick ? 60 : 600;
    } else if (name == "large_pyramid") {
        add_pyramid(s, 100, 0, 0);
        s.grounds.push_back({-110, 110});
        s.ground_y.push_back(0);
        s.warmup = quick ? 10 : 60;
        s.steps = quick ? 20 : 200;
    } else {
        // Rows of pyramids 12 m apart, each row on its own ground 15 m above the last.
        for (int row = 0; row < 20; ++row) {
            const float y = 15.0f * static_cast<float>(row);
            s.grounds.push_back({-130, 130});
            s.ground_y.push_back(y);
            for (int col = 0; col < 20; ++col) add_pyramid(s, 10, -114 + 12.0f * static_cast<float>(col), y);
        }
        s.warmup = quick ? 5 : 30;
        s.steps = quick ? 10 : 60;
    }
    return s;
}

double thread_cpu_ms() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

struct result {
    double best_ms = 1e300;  // CPU ms per step, best run
    bool standing = true;
    float worst_top_drift = 0;  // m
};

// A top box at (x, y) at the end: standing, or fallen (see the header).
void check_top(const scene& s, size_t top, float x, float y, result& r) {
    const box_at start = s.boxes[top];
    const float drift = std::hypot(x - start.x, y - start.y);
    r.worst_top_drift = std::max(r.worst_top_drift, drift);
    const float ground = s.ground_y[s.ground_y.size() == 1 ? 0 : static_cast<size_t>(start.y / 15.0f)];
    if (std::abs(x - start.x) > 0.25f || y - ground < 0.9f * (start.y - ground)) r.standing = false;
}

void run_arena(const scene& s, result& r) {
    world::world_config c;
    c.gravity = {0, -10};
    c.air_density = 0;
    c.boundary = world::boundary::open;
    c.max_bodies = static_cast<uint32_t>(s.boxes.size() + s.grounds.size() + 16);
    c.rocks.count = 0;
    world::world w(c, 1);
    world::body_material ground;
    for (size_t g = 0; g < s.grounds.size(); ++g) {
        const std::vector<world::vec2> line{{s.grounds[g].first, s.ground_y[g]}, {s.grounds[g].second, s.ground_y[g]}};
        w.add_chain(line, ground);
    }
    world::body_material m;
    m.density = 1;
    m.friction = 0.6f;
    m.restitution = 0;
    const world::shape box = world::make_box(0.5f, 0.5f);
    std::vector<uint32_t> ids;
    for (const box_at& b : s.boxes) ids.push_back(*w.add_body(world::make_body(m, box, {b.x, b.y}), box));
    for (int k = 0; k < s.warmup; ++k) w.step({});
    const double t0 = thread_cpu_ms();
    for (int k = 0; k < s.steps; ++k) w.step({});
    r.best_ms = std::min(r.best_ms, (thread_cpu_ms() - t0) / s.steps);
    for (size_t top : s.tops) {
        const world::body& b = *w.find(ids[top]);
        check_top(s, top, b.position.x(), b.position.y(), r);
    }
}

void run_box2d(const scene& s, result& r) {
    b2World w(b2Vec2(0, -10));
    w.SetAllowSleeping(false);
    for (size_t g = 0; g < s.grounds.size(); ++g) {
        b2BodyDef def;
        b2Body* ground = w.CreateBody(&def);
        b2EdgeShape edge;
        edge.SetTwoSided(b2Vec2(s.grounds[g].first, s.ground_y[g]), b2Vec2(s.grounds[g].second, s.ground_y[g]));
        ground->CreateFixture(&edge, 0);
    }
    b2PolygonShape box;
    box.SetAsBox(0.5f, 0.5f);
    b2FixtureDef fixture;
    fixture.shape = &box;
    fixture.density = 1;
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
    for (int k = 0; k < s.warmup; ++k) w.Step(1.0f / 60.0f, 8, 3);
    const double t0 = thread_cpu_ms();
    for (int k = 0; k < s.steps; ++k) w.Step(1.0f / 60.0f, 8, 3);
    r.best_ms = std::min(r.best_ms, (thread_cpu_ms() - t0) / s.steps);
    for (size_t top : s.tops) {
        const b2Vec2 p = bodies[top]->GetPosition();
        check_top(s, top, p.x, p.y, r);
    }
}

}  // namespace

int main(int argc, char** argv) {
    const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
    const int runs = quick ? 1 : 2;
    for (const char* name : {"pyramid", "large_pyramid", "many_pyramids"}) {
        const scene s = make_scene(name, quick);
        result arena_r, box2d_r;
        for (int k = 0; k < runs; ++k) {
            run_arena(s, arena_r);
            run_box2d(s, box2d_r);
        }
        for (const auto& [engine, r] : {std::pair{"arena", arena_r}, std::pair{"box2d-2.4.1", box2d_r}}) {
            std::printf(
                "{\"bench\":\"pyramids\",\"scene\":\"%s\",\"engine\":\"%s\",\"boxes\":%zu,\"steps\":%d,\"runs\":%d,"
                "\"cpu_ms_per_step\":%.4f,\"standing\":%s,\"worst_top_drift_m\":%.4f}\n",
                name, engine, s.boxes.size(), s.steps, runs, r.best_ms, r.standing ? "true" : "false",
                static_cast<double>(r.worst_top_drift));
        }
        std::fflush(stdout);
    }
    return 0;
}
