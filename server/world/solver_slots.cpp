#include "server/world/solver_slots.hpp"

namespace arena::world {

void solver_slots::gather(std::span<const body> bodies, std::span<contact> contacts) {
    slots_.assign(1, body_slot{});
    body_of_.assign(1, 0);
    if (slot_of_.size() < bodies.size()) slot_of_.resize(bodies.size(), 0);
    auto slot_for = [&](uint32_t index) -> uint32_t {
        const body& b = bodies[index];
        if (b.is_static()) return 0;
        uint32_t& s = slot_of_[index];
        if (s == 0) {
            s = static_cast<uint32_t>(slots_.size());
            slots_.push_back({b.velocity, b.angular_velocity, b.inv_mass, b.inv_inertia, {0, 0}, 0});
            body_of_.push_back(index);
        }
        return s;
    };
    for (contact& c : contacts) {
        c.slot_a = slot_for(c.a);
        c.slot_b = c.with == wall::none ? slot_for(c.b) : 0;
    }
}

void solver_slots::release() {
    for (size_t s = 1; s < body_of_.size(); ++s) slot_of_[body_of_[s]] = 0;
}

}  // namespace arena::world
