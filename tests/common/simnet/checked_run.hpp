#pragma once
// A match and its clients over the simulated network, with every Input handed to the match,
// every input the world applied and every snapshot's ack checked against the rule
// (input_ledger) as they happen. The tests read the counters, and the sequences each client's
// inputs were consumed in.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <vector>

#include "server/world/presets.hpp"
#include "simnet/input_ledger.hpp"
#include "simnet/match_sim.hpp"

namespace arena::simnet {

struct checked_run {
    match_sim sim;
    std::vector<input_ledger> ledgers;
    std::vector<std::vector<std::uint32_t>> consumed;  // per client: the sequence consumed at each tick
    std::map<std::uint32_t, std::size_t> client_of_body;
    std::uint64_t inputs_applied = 0;
    std::uint64_t inputs_not_as_ruled = 0;  // the world applied another input than the rule says
    std::uint64_t acks_checked = 0;
    std::uint64_t acks_not_as_ruled = 0;      // a snapshot acknowledged another input than the last consumed
    std::uint64_t arrivals_out_of_order = 0;  // on a stream: an Input that is not the next one

    checked_run(const match::match_config& config, const sim_options& options)
        : sim(config, *world::preset_by_name("asteroids"), options) {
        ledgers.assign(sim.size(), input_ledger(config.input_buffer));
        consumed.resize(sim.size());
        const bool stream = options.kind == link_kind::stream;
        for (std::size_t i = 0; i < sim.size(); ++i) {
            sim.server(i).on_input = [this, i, stream](const protocol::input_msg& in) {
                if (stream && in.sequence != ledgers[i].last_received() + 1) ++arrivals_out_of_order;
                ledgers[i].received(in);
            };
            sim.server(i).on_snapshot_ack = [this, i](std::uint32_t ack) {
                ++acks_checked;
                if (ack != ledgers[i].consumed_sequence()) ++acks_not_as_ruled;
            };
        }
        sim.match().on_tick = [this](const match::tick_record& record, std::uint64_t) {
            for (std::size_t i = 0; i < sim.size(); ++i)
                if (const std::uint32_t body = sim.server(i).body_id()) client_of_body[body] = i;
            for (const world::body_input& applied : record.inputs) {
                const auto it = client_of_body.find(applied.body_id.value());
                if (it == client_of_body.end()) continue;  // spawned this tick: no Welcome out yet
                const world::player_input ruled = ledgers[it->second].consume();
                consumed[it->second].push_back(ledgers[it->second].consumed_sequence());
                ++inputs_applied;
                if (ruled.thrust != applied.input.thrust || ruled.turn != applied.input.turn ||
                    ruled.buttons != applied.input.buttons)
                    ++inputs_not_as_ruled;
            }
        };
    }

    // Sequences that were never consumed between the first and the last consumed one: each
    // is an input the world never applied (lost, overtaken, or dropped by a full buffer); the
    // largest number when one was consumed after a newer one.
    [[nodiscard]] std::uint64_t gaps(std::size_t client) const {
        std::uint64_t missing = 0;
        std::uint32_t last = 0;
        for (const std::uint32_t s : consumed[client]) {
            if (s == last) continue;  // the same input again: an underrun repeats it, not consumed twice
            if (s < last) return std::numeric_limits<std::uint64_t>::max();  // an older one after a newer one
            if (last != 0) missing += s - last - 1;
            last = s;
        }
        return missing;
    }
};

}  // namespace arena::simnet
