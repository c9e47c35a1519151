// The step's per-phase profile: every phase timed once per step, in order, through the
// caller's clock, and the results bit for bit those of an untimed world.
#include <catch2/catch.hpp>

#include <vector>

#include "server/world/presets.hpp"
#include "server/world/profile.hpp"
#include "server/world/world.hpp"

using namespace arena::world;

namespace {

// A clock that advances by one "nanosecond" per reading and logs nothing else: a phase that
// is lapped exactly once per step gets exactly 1 per step.
struct counting_clock {
    int64_t readings = 0;
};

int64_t count_reading(void* context) {
    auto* c = static_cast<counting_clock*>(context);
    return c->readings++;
}

}  // namespace

TEST_CASE("each phase of the step is lapped once per step, and timing changes no result", "[world][profile]") {
    for (const world_config& config : {asteroids_preset(), platformer_preset(), pyramid_preset(6)}) {
        world timed(config, 11), plain(config, 11);
        const body_id a = *timed.spawn_player(player_id{1});
        REQUIRE(*plain.spawn_player(player_id{1}) == a);
        counting_clock clock;
        timed.set_step_timer({count_reading, &clock});
        const int steps = 50;
        for (int k = 0; k < steps; ++k) {
            const uint8_t buttons = k % 10 == 0 ? button_impulse : 0;
            const tick_inputs inputs{{a, {1.0f, 0.5f, buttons}}};
            timed.step(inputs);
            plain.step(inputs);
            REQUIRE(timed.hash() == plain.hash());
        }
        const step_profile& p = timed.profile();
        CHECK(p.steps == steps);
        for (size_t i = 0; i < step_phase_count; ++i) {
            INFO(step_phase_name(static_cast<step_phase>(i)));
            CHECK(p.ns[i] == steps);
        }
        // One reading to start each step, then one per phase.
        CHECK(clock.readings == steps * static_cast<int64_t>(step_phase_count + 1));
        CHECK(p.ms(step_phase::solver) == Approx(1e-6));
        CHECK(plain.profile().steps == 0);

        // Off again: no more readings.
        timed.set_step_timer({});
        timed.step({});
        CHECK(clock.readings == steps * static_cast<int64_t>(step_phase_count + 1));
        timed.reset_profile();
        CHECK(timed.profile().steps == 0);
        CHECK(timed.profile().total_ms() == 0);
    }
}
