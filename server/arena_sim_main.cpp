// arena-sim: the world from the command line. One body and one scenario with CSV out, a whole
// preset with its final hash, or a plot of the integrators against the exact solution.
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <fstream>
#include <string>
#include <variant>

#include "server/cli_helpers.hpp"
#include "server/config/config_json.hpp"
#include "server/sim/single_body.hpp"
#include "server/sim/svg_plot.hpp"
#include "server/world/presets.hpp"
#include "server/world/world.hpp"

using namespace arena;

namespace {

constexpr uint32_t max_plot_steps = 1000;

int run_single_body(const sim::single_body_scenario& s) {
    std::printf("t,x,y,vx,vy,angle,omega\n");
    for (const sim::sample& r : sim::run_scenario(s))
        std::printf("%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", r.t, r.x, r.y, r.vx, r.vy, r.angle, r.omega);
    return 0;
}

// The world's step timer (server/world/profile.hpp) on the steady clock.
int64_t steady_now_ns(void*) {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

// Every body as CSV, in id order: what a run ended with, checkable from outside.
void print_final_state(const world::world& w) {
    std::printf("id,x,y,angle,vx,vy,omega\n");
    for (const world::body& b : w.bodies())
        std::printf("%u,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", b.id, b.position.x(), b.position.y(), b.angle, b.velocity.x(),
                    b.velocity.y(), b.angular_velocity);
}

int run_preset(world::world_config config, uint32_t bodies, bool bodies_given, uint32_t steps, uint64_t seed,
               bool final_state, bool profile) {
    if (bodies_given) {
        // Every rock is a body: beyond max_bodies the world would only stop spawning.
        if (bodies > config.max_bodies) {
            std::fprintf(stderr, "arena-sim: --bodies: at most %u (the world's max_bodies), got %u\n",
                         config.max_bodies, bodies);
            return 2;
        }
        // Keep the preset's crowding: the world grows with the square root of the rock count.
        if (config.rocks.count > 0 && bodies > config.rocks.count) {
            const float scale = std::sqrt(static_cast<float>(bodies) / static_cast<float>(config.rocks.count));
            config.size *= scale;
        }
        config.rocks.count = bodies;
    }
    world::world w(config, seed);
    if (profile) w.set_step_timer({steady_now_ns, nullptr});
    const auto start = std::chrono::steady_clock::now();
    for (uint32_t k = 0; k < steps; ++k) w.step({});
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("bodies=%zu steps=%u\n", w.bodies().size(), steps);
    std::printf("hash=%016" PRIx64 "\n", w.hash());
    std::printf("ms_per_step=%.4f\n", steps ? seconds * 1e3 / steps : 0.0);
    if (profile) {
        // Mean ms per step in each phase of world::step, then their sum.
        std::printf("profile_ms");
        for (size_t i = 0; i < world::step_phase_count; ++i) {
            const auto phase = static_cast<world::step_phase>(i);
            std::printf(" %s=%.4f", world::step_phase_name(phase), w.profile().ms(phase));
        }
        std::printf(" total=%.4f\n", w.profile().total_ms());
    }
    if (final_state) print_final_state(w);
    return 0;
}

int write_plot(const sim::single_body_scenario& base, const std::string& path) {
    const double total = static_cast<double>(base.steps) * base.dt;
    // Which axis moves most decides what the chart shows.
    const auto coarse = sim::run_scenario(base);
    const bool along_y = !coarse.empty() && std::fabs(coarse.back().y) > std::fabs(coarse.back().x);
    auto pick = [along_y](const sim::sample& r) {
        return static_cast<double>(along_y ? r.y : r.x);
    };

    std::vector<sim::series> lines;
    for (int divide : {1, 2, 4, 10}) {
        sim::single_body_scenario s = base;
        s.dt = base.dt / static_cast<float>(divide);
        s.steps = base.steps * static_cast<uint32_t>(divide);
        sim::series line{"dt = " + std::to_string(s.dt).substr(0, 6) + " s", {0}, {0}};
        for (const sim::sample& r : sim::run_scenario(s)) {
            line.xs.push_back(r.t);
            line.ys.push_back(pick(r));
        }
        lines.push_back(line);
    }
    sim::series truth{"exact", {}, {}, true};
    if (sim::exact_solution(base, 0)) {
        for (int k = 0; k <= 200; ++k) {
            const double t = total * k / 200;
            truth.xs.push_back(t);
            truth.ys.push_back(pick(*sim::exact_solution(base, t)));
        }
    } else {
        // No closed form with friction or drag: a run at Δt/1000 stands in for it.
        sim::single_body_scenario fine = base;
        fine.dt = base.dt / 1000;
        fine.steps = base.steps * 1000;
        truth.label = "reference (dt/1000)";
        truth.xs.push_back(0);
        truth.ys.push_back(0);
        for (const sim::sample& r : sim::run_scenario(fine)) {
            truth.xs.push_back(r.t);
            truth.ys.push_back(pick(r));
        }
    }
    lines.push_back(truth);
    const char* method =
        base.integrator == world::integrator::explicit_euler ? "explicit Euler" : "semi-implicit Euler";
    std::ofstream out(path);
    out << sim::render_svg(std::string("Impact of delta time: ") + method, "t (s)", along_y ? "y (m)" : "x (m)", lines);
    if (!out) {
        std::fprintf(stderr, "arena-sim: cannot write %s\n", path.c_str());
        return 1;
    }
    std::printf("wrote %s\n", path.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"arena-sim: run the Arena world from the command line", "arena-sim"};
    sim::single_body_scenario s;
    std::string integrator = "semi-implicit", preset, config_file, plot;
    uint32_t bodies = 0, base = 20;
    bool final_state = false;
    uint64_t seed = 1;
    app.add_option("--integrator", integrator, "semi-implicit (default) or explicit")
        ->check(CLI::IsMember({"semi-implicit", "explicit"}));
    app.add_option("--dt", s.dt, "time step, s (default 1)");
    app.add_option("--steps", s.steps, "number of steps (default 10)");
    app.add_option("--mass", s.mass, "body mass, kg (default 1)");
    cli::add_vec2_option(app, "--force", s.force, "constant force applied every step, N");
    cli::add_vec2_option(app, "--velocity", s.velocity, "initial velocity, m/s");
    cli::add_vec2_option(app, "--gravity", s.gravity, "gravity, m/s² (e.g. 0,-9.81)");
    app.add_option("--friction", s.friction, "kinetic friction coefficient μ: the body slides on a floor, N = m·|g|");
    app.add_option("--density", s.density, "density of the medium ρ, kg/m³ (drag)");
    app.add_option("--drag-coefficient", s.drag_coefficient, "drag coefficient Cd");
    app.add_option("--area", s.area, "frontal area A, m²");
    app.add_option("--preset", preset, "run a whole preset (asteroids, platformer, pyramid) and print its final hash");
    auto* base_opt = app.add_option("--base", base, "boxes in the bottom row of --preset pyramid (default 20)")
                         ->check(CLI::Range(1u, 1000u));
    app.add_flag("--final-state", final_state,
                 "after a --preset/--config run, print every body as CSV: id,x,y,angle,vx,vy,omega");
    app.add_option("--config", config_file, "run a whole world from a JSON config file");
    auto* bodies_opt = app.add_option("--bodies", bodies, "rock count for --preset/--config");
    app.add_option("--seed", seed, "seed for --preset/--config (default 1)");
    bool profile = false;
    app.add_flag("--profile", profile,
                 "with --preset/--config: print the mean ms per step of each phase of the world step");
    app.add_option("--plot", plot, "write an SVG of the trajectory for several dt against the exact solution");
    if (int code = cli::parse_or_exit_code(app, argc, argv); code >= 0) return code;

    s.integrator = integrator == "explicit" ? world::integrator::explicit_euler : world::integrator::semi_implicit;
    if (profile && preset.empty() && config_file.empty()) {
        std::fprintf(stderr, "arena-sim: --profile: times a whole world's step: give --preset or --config\n");
        return 2;
    }
    if (!preset.empty() || !config_file.empty()) {
        world::world_config config;
        if (!config_file.empty()) {
            auto loaded = config::load_config_file(config_file);
            if (!loaded) {
                std::fprintf(stderr, "arena-sim: %s\n", loaded.error.c_str());
                return 2;
            }
            config = std::move(loaded.value);
        } else if (preset == "pyramid") {
            config = world::pyramid_preset(base);
        } else if (auto p = world::preset_by_name(preset)) {
            config = *p;
        } else {
            std::fprintf(stderr, "arena-sim: --preset: unknown preset '%s' (asteroids, platformer, pyramid)\n",
                         preset.c_str());
            return 2;
        }
        if (base_opt->count() > 0 && preset != "pyramid") {
            std::fprintf(stderr, "arena-sim: --base: only for --preset pyramid\n");
            return 2;
        }
        return run_preset(config, bodies, bodies_opt->count() > 0, s.steps, seed, final_state, profile);
    }
    if (auto problem = sim::check_scenario(s)) {
        std::fprintf(stderr, "arena-sim: %s\n", problem->c_str());
        return 2;
    }
    // The plot's reference run takes 1000 times as many steps as asked for.
    if (!plot.empty() && s.steps > max_plot_steps) {
        std::fprintf(stderr, "arena-sim: --plot: at most %u steps (the reference runs 1000 times as many), got %u\n",
                     max_plot_steps, s.steps);
        return 2;
    }
    if (!plot.empty()) return write_plot(s, plot);
    return run_single_body(s);
}
