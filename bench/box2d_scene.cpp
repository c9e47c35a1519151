// arena-bench-box2d-scene: our world on the scene of ../shared/peers/box2d (bench_scene.hpp),
// so that run_all.py can interleave it with Box2D and table.py can set them side by side.
//
// Same scene and material: r = 1 m, density 1 (mass π kg), restitution 0.5, no friction (our
// world has none between bodies), no gravity, dt = 1/60 s, walls on the world border, 8
// velocity and 3 position iterations like Box2D 2.4's Step(dt, 8, 3). Box2D's linear damping
// 0.1 1/s is applied as a force −c·m·v on every body before each step (our world has no
// linear damping setting); that loop is inside the timed region. Our walls span [0, L], so
// the scene is shifted by +L/2 and shifted back for count_overlaps.
#include <bench_scene.hpp>

#include "server/world/world.hpp"

using namespace arena;

int main(int argc, char** argv) {
    bench::Params p = bench::parse_args(argc, argv);
    const auto t_setup = bench::Clock::now();
    bench::Scene scene = bench::make_scene(p);
    const double side = 2.0 * scene.half_extent;

    world::world_config config;
    config.dt = p.dt;
    config.gravity = {0, 0};
    config.boundary = world::boundary::walls;
    config.size = {static_cast<float>(side), static_cast<float>(side)};
    config.angular_damping = 0;
    config.velocity_iterations = static_cast<uint32_t>(p.vel_iters);
    config.position_iterations = static_cast<uint32_t>(p.pos_iters);
    config.restitution_threshold = 1.0f;  // Box2D's default b2_velocityThreshold
    config.max_bodies = static_cast<uint32_t>(p.n) + 16;
    config.rocks.count = 0;
    world::world w(config, p.seed);
    world::body_material material;
    material.radius = static_cast<float>(p.radius);
    material.density = p.density;
    material.restitution = p.restitution;
    material.drag_area = 0;
    for (const bench::BodyInit& b : scene.bodies) {
        world::body body = world::make_body(
            material, {static_cast<float>(b.x + scene.half_extent), static_cast<float>(b.y + scene.half_extent)});
        body.velocity = {static_cast<float>(b.vx), static_cast<float>(b.vy)};
        w.add_body(body);
    }
    const double setup_ms = bench::ms_since(t_setup, bench::Clock::now());

    const float damping = p.linear_damping;
    auto step = [&] {
        for (world::body& b : w.bodies()) b.apply_force(b.velocity * (-damping * b.mass));
        w.step({});
    };
    for (int k = 0; k < p.warmup; ++k) step();
    std::vector<double> ms;
    ms.reserve(static_cast<size_t>(p.steps));
    const auto t_timed = bench::Clock::now();
    for (int k = 0; k < p.steps; ++k) {
        const auto t0 = bench::Clock::now();
        step();
        ms.push_back(bench::ms_since(t0, bench::Clock::now()));
    }
    const double timed_s = bench::ms_since(t_timed, bench::Clock::now()) / 1e3;

    std::vector<bench::BodyInit> final_state;
    double speed_sum = 0;
    long touching = 0;
    for (const world::body& b : w.bodies()) {
        final_state.push_back(
            {b.position.x() - scene.half_extent, b.position.y() - scene.half_extent, b.velocity.x(), b.velocity.y()});
        speed_sum += std::sqrt(static_cast<double>(b.velocity.squaredNorm()));
    }
    for (const world::contact& c : w.last_contacts())
        if (c.separation <= 0) ++touching;

    bench::Report r{};
    r.engine = "arena";
    r.version = "world_version " + std::to_string(world::world_version);
    r.build = "Release -O3 -ffp-contract=off";
    r.p = p;
    r.scene = &scene;
    r.st = bench::summarize(ms);
    r.setup_ms = setup_ms;
    r.total_timed_s = timed_s;
    r.contacts_touching = touching;
    r.contact_pairs = static_cast<long>(w.last_contacts().size());
    r.awake_bodies = static_cast<long>(w.bodies().size());
    r.mean_speed = speed_sum / static_cast<double>(w.bodies().size());
    r.overlaps = bench::count_overlaps(final_state, p.radius, scene.half_extent);
    bench::print_json(r);
    return 0;
}
