#pragma once
// Where a world step spends its time, phase by phase, like Box2D's b2Profile: read by
// `arena-sim --profile` and `make bench`. The world never reads a clock: whoever wants a
// profile hands the world a step_timer (a function that returns nanoseconds from any fixed
// origin). Without one, step() tests a null pointer once per phase and reads nothing; with one,
// the state and its hash are the same (the timer only ever writes the profile).
#include <array>
#include <cstddef>
#include <cstdint>

namespace arena::world {

// With world_config::substeps > 1 the sub-steps integrate velocities and positions themselves:
// forces_velocities is the forces alone, solver the whole of the sub-steps (integration, warm
// starts, soft and relax passes, restitution), positions the clearing and wrapping, correction
// who stands on what.
enum class step_phase : uint8_t {
    inputs,             // apply_inputs
    forces_velocities,  // forces, resistance and velocity integration
    broadphase,         // the static bodies' index (when it changed), the grid, the bodies bucketed by cell
    narrow_phase,       // candidate pairs tested, their manifolds, static-body and wall manifolds
    solver,             // warm start and the velocity iterations
    positions,          // position integration (and wrapping of bodies in no contact)
    correction,         // the position iterations, wrapping of bodies in contacts, who stands on what
};
inline constexpr std::size_t step_phase_count = 7;

inline constexpr const char* step_phase_name(step_phase p) {
    constexpr const char* names[step_phase_count] = {"inputs", "forces_velocities", "broadphase", "narrow_phase",
                                                     "solver", "positions",         "correction"};
    return names[static_cast<std::size_t>(p)];
}

// The caller's clock. `now_ns` must be non-decreasing.
struct step_timer {
    int64_t (*now_ns)(void* context) = nullptr;
    void* context = nullptr;
};

// Nanoseconds per phase summed over `steps` steps.
struct step_profile {
    std::array<int64_t, step_phase_count> ns{};
    uint64_t steps = 0;

    // Mean milliseconds per step in phase p (0 before any step).
    double ms(step_phase p) const {
        return steps ? static_cast<double>(ns[static_cast<std::size_t>(p)]) * 1e-6 / static_cast<double>(steps) : 0;
    }
    double total_ms() const {
        double sum = 0;
        for (std::size_t i = 0; i < step_phase_count; ++i) sum += ms(static_cast<step_phase>(i));
        return sum;
    }
};

// One step's stopwatch: each lap() charges the time since the previous lap (or the start) to a
// phase. Inert without a timer.
class phase_laps {
public:
    phase_laps(const step_timer& timer, step_profile& profile) : timer_(timer), profile_(profile) {
        if (timer_.now_ns) last_ = timer_.now_ns(timer_.context);
    }
    void lap(step_phase p) {
        if (!timer_.now_ns) return;
        const int64_t now = timer_.now_ns(timer_.context);
        profile_.ns[static_cast<std::size_t>(p)] += now - last_;
        last_ = now;
    }
    void finish() {
        if (timer_.now_ns) ++profile_.steps;
    }

private:
    const step_timer& timer_;
    step_profile& profile_;
    int64_t last_ = 0;
};

}  // namespace arena::world
