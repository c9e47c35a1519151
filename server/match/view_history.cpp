#include "server/match/view_history.hpp"

#include "server/match/body_state.hpp"

namespace arena::match {

namespace delta = protocol::delta;

quantized_history::quantized_history(tick_ring ring) : ring_(ring), entries_(ring.depth) {}

const std::vector<delta::quantized_body>& quantized_history::record(uint32_t tick,
                                                                    std::span<const world::body> bodies) {
    entry& e = entries_[ring_.slot(tick)];
    e.tick = tick;
    e.bodies.clear();  // keeps its capacity: no allocation once the world stops growing
    for (const world::body& b : bodies) e.bodies.push_back(delta::quantize(body_state(b)));
    return e.bodies;
}

const std::vector<delta::quantized_body>* quantized_history::at(uint32_t tick) const {
    const entry& e = entries_[ring_.slot(tick)];
    return tick != 0 && e.tick == tick ? &e.bodies : nullptr;
}

client_views::client_views(tick_ring ring) : ring_(ring), entries_(ring.depth) {}

void client_views::record(uint32_t tick, std::span<const uint32_t> indices, std::span<const held_body> held) {
    entry& e = entries_[ring_.slot(tick)];
    e.tick = tick;
    e.indices.assign(indices.begin(), indices.end());
    e.held.assign(held.begin(), held.end());
    e.game = 0;
}

void client_views::record_game(uint32_t tick, uint32_t version) {
    entry& e = entries_[ring_.slot(tick)];
    if (e.tick == tick) e.game = version;
}

uint32_t client_views::game_at(uint32_t tick) const {
    const entry& e = entries_[ring_.slot(tick)];
    return tick != 0 && e.tick == tick ? e.game : 0;
}

std::span<const client_views::held_body> client_views::held_at(uint32_t tick) const {
    const entry& e = entries_[ring_.slot(tick)];
    return tick != 0 && e.tick == tick ? std::span<const held_body>(e.held) : std::span<const held_body>();
}

const std::vector<uint32_t>* client_views::at(uint32_t tick) const {
    const entry& e = entries_[ring_.slot(tick)];
    return tick != 0 && e.tick == tick ? &e.indices : nullptr;
}

}  // namespace arena::match
