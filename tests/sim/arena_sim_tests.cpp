// arena-sim as a user runs it.
#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "common/run_command.hpp"
#include "server/sim/single_body.hpp"

namespace {

struct run_result {
    int status;
    std::string out;
};

run_result run(const std::string& args) {
    const auto r = arena::test::run_command(arena::test::program("arena-sim") + " " + args + " 2>&1");
    return {r.exit_code, r.output};
}

std::string last_line(const std::string& text) {
    const auto end = text.find_last_not_of('\n');
    const auto start = text.rfind('\n', end);
    return text.substr(start == std::string::npos ? 0 : start + 1,
                       end - (start == std::string::npos ? 0 : start + 1) + 1);
}

}  // namespace

TEST_CASE("arena-sim prints the lecture's explicit Euler table", "[sim]") {
    const run_result r = run("--integrator explicit --dt 1 --steps 10 --mass 1 --force 10,0");
    REQUIRE(r.status == 0);
    CHECK(r.out.rfind("t,x,y,vx,vy,angle,omega\n1,0,0,10,0,0,0\n2,10,0,20,0,0,0\n", 0) == 0);
    CHECK(last_line(r.out) == "10,450,0,100,0,0,0");
}

TEST_CASE("arena-sim defaults to semi-implicit Euler", "[sim]") {
    const run_result r = run("--dt 1 --steps 10 --force 10,0");
    REQUIRE(r.status == 0);
    CHECK(last_line(r.out) == "10,550,0,100,0,0,0");
}

TEST_CASE("arena-sim slides a body to rest under friction", "[sim]") {
    const run_result r = run("--dt 0.01 --steps 400 --velocity 10,0 --gravity 0,-9.81 --friction 0.5");
    REQUIRE(r.status == 0);
    std::istringstream row(last_line(r.out));
    double t, x, y, vx;
    char comma;
    row >> t >> comma >> x >> comma >> y >> comma >> vx;
    CHECK(vx == 0.0);
    CHECK(y == 0.0);
    CHECK(x == Approx(100 / (2 * 0.5 * 9.81)).epsilon(0.01));
}

TEST_CASE("arena-sim runs a preset and prints its hash and step time", "[sim]") {
    const run_result a = run("--preset asteroids --bodies 200 --steps 60 --seed 3");
    const run_result b = run("--preset asteroids --bodies 200 --steps 60 --seed 3");
    REQUIRE(a.status == 0);
    const auto at = a.out.find("hash=");
    REQUIRE(at != std::string::npos);
    CHECK(a.out.substr(at, 22) == b.out.substr(b.out.find("hash="), 22));
    CHECK(a.out.find("ms_per_step=") != std::string::npos);
    CHECK(a.out.find("bodies=200") != std::string::npos);
}

TEST_CASE("arena-sim draws the impact of the time step as an SVG", "[sim]") {
    const std::string path = "/tmp/arena-sim-test-" + std::to_string(::getpid()) + ".svg";
    const run_result r = run("--integrator explicit --dt 1 --steps 10 --force 10,0 --plot " + path);
    REQUIRE(r.status == 0);
    std::ifstream in(path);
    std::string svg((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    CHECK(svg.rfind("<svg", 0) == 0);
    CHECK(svg.find("exact") != std::string::npos);
    CHECK(svg.find("dt = 1.0000 s") != std::string::npos);
    CHECK(svg.find("dt = 0.1000 s") != std::string::npos);
    std::remove(path.c_str());
}

TEST_CASE("arena-sim refuses bad flags with a one-line error and exit code 2", "[sim]") {
    for (const char* args :
         {"--frobnicate", "--force 1,x", "--integrator leapfrog", "--friction 0.5", "--preset tetris", "--dt -1"}) {
        INFO(args);
        const run_result r = run(args);
        CHECK(r.status == 2);
        CHECK(r.out.find("arena-sim:") == 0);
        CHECK(r.out.find('\n') == r.out.size() - 1);  // one line
    }
}

TEST_CASE("the exact solution is known only for constant acceleration", "[sim]") {
    arena::sim::single_body_scenario s;
    s.force = {10, 0};
    REQUIRE(arena::sim::exact_solution(s, 10));
    CHECK(arena::sim::exact_solution(s, 10)->x == 500.0f);
    s.friction = 0.1f;
    CHECK_FALSE(arena::sim::exact_solution(s, 10));
}

TEST_CASE("arena-sim refuses sizes it cannot hold with a usage error, not bad_alloc", "[sim][limits]") {
    // Each of these aborted with std::bad_alloc (exit 134) before.
    const run_result bodies = run("--preset asteroids --bodies 100000000 --steps 1");
    CHECK(bodies.status == 2);
    CHECK(bodies.out == "arena-sim: --bodies: at most 1048576 (the world's max_bodies), got 100000000\n");
    const run_result steps = run("--steps 4000000000");
    CHECK(steps.status == 2);
    CHECK(steps.out == "arena-sim: --steps must be at most 1000000 for one body (one row per step), got 4000000000\n");
    const run_result plot = run("--steps 5000 --plot /tmp/arena-sim-never-written.svg");
    CHECK(plot.status == 2);
    CHECK(plot.out.find("--plot: at most 1000 steps") != std::string::npos);
    // At the bounds they run.
    CHECK(run("--dt 0.001 --steps 1000000 > /dev/null").status == 0);
}

TEST_CASE("arena-sim --bodies is honoured up to max_bodies, and max_bodies limits a config's rocks", "[sim][limits]") {
    const std::string path = "/tmp/arena-sim-test-max-bodies.json";
    std::ofstream(path) << R"({"max_bodies": 10, "rocks": {"count": 100}})";
    const run_result r = run("--config " + path + " --steps 1");
    CHECK(r.status == 0);
    CHECK(r.out.rfind("bodies=10 steps=1\n", 0) == 0);
    std::remove(path.c_str());
}

TEST_CASE("arena-sim --profile prints every phase of the step and leaves the hash alone", "[sim][profile]") {
    const run_result plain = run("--preset asteroids --bodies 500 --steps 30 --seed 4");
    const run_result timed = run("--preset asteroids --bodies 500 --steps 30 --seed 4 --profile");
    REQUIRE(plain.status == 0);
    REQUIRE(timed.status == 0);
    CHECK(plain.out.find("profile_ms") == std::string::npos);
    CHECK(timed.out.substr(timed.out.find("hash="), 22) == plain.out.substr(plain.out.find("hash="), 22));
    const std::string line = last_line(timed.out);
    INFO(line);
    REQUIRE(line.rfind("profile_ms ", 0) == 0);
    double sum = 0, total = -1;
    for (const char* phase :
         {"inputs", "forces_velocities", "broadphase", "narrow_phase", "solver", "positions", "correction", "total"}) {
        const auto at = line.find(std::string(" ") + phase + "=");
        REQUIRE(at != std::string::npos);
        const double ms = std::stod(line.substr(at + std::string(phase).size() + 2));
        CHECK(ms >= 0);
        if (std::string(phase) == "total") {
            total = ms;
        } else {
            sum += ms;
        }
    }
    CHECK(total > 0);
    CHECK(total == Approx(sum).margin(1e-3));

    const run_result single = run("--profile");
    CHECK(single.status == 2);
    CHECK(single.out.find("arena-sim: --profile") == 0);
}
