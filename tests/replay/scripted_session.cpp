#include "scripted_session.hpp"

#include <map>

#include "scenes/sticks.hpp"
#include "server/match/tick_record.hpp"
#include "server/replay/recorder.hpp"
#include "server/world/presets.hpp"
#include "server/world/rng.hpp"

namespace arena::replay::testing {

namespace {

struct scheduled {
    uint32_t tick;
    uint32_t owner;
    bool join;  // false: the owner's body leaves
};

// Two join in the first tick, more later, two leave; owner 5 joins after a leave, so its body
// id is above removed ones.
constexpr scheduled schedule[] = {
    {0, 1, true}, {0, 2, true}, {45, 3, true}, {130, 4, true}, {300, 2, false}, {420, 5, true}, {500, 4, false},
};

// A player's stick, held for a while like a human's, then moved.
struct player {
    world::body_id body_id;
    world::player_input stick{};
};

world::tick_inputs draw_inputs(world::rng& script, std::map<world::player_id, player>& players) {
    world::tick_inputs inputs;
    for (auto& [owner, p] : players) {  // std::map: owner order, never hash order
        scenes::move_stick_now_and_then(script, p.stick);
        const bool sent = script.next_u64() % 10 != 0;  // a jittery client misses a tick now and then
        const bool fire = script.next_u64() % 40 == 0;
        if (!sent) continue;
        world::player_input in = p.stick;
        in.buttons = fire ? world::button_impulse : 0;
        inputs.push_back({p.body_id, in});
    }
    return inputs;
}

}  // namespace

protocol::result<session_result> record_scripted_session(const std::string& path, const session_script& script) {
    using r = protocol::result<session_result>;
    const auto config = world::preset_by_name(script.preset);
    if (!config) return r::failure("unknown preset " + script.preset);
    world::world w(*config, script.world_seed);
    auto opened =
        recorder::open(path, make_header(w, script.preset, script.world_seed, script.tick_rate, script.hash_interval));
    if (!opened) return r::failure(opened.error);
    recorder& rec = opened.value;

    session_result out;
    out.hashes.push_back(w.hash());
    world::rng inputs_rng(script.script_seed);
    std::map<world::player_id, player> players;  // by owner
    for (uint32_t k = 0; k < script.ticks; ++k) {
        match::tick_record record;
        record.tick = w.tick();
        // Inputs come from players already in the world; this tick's joins send from the next.
        record.inputs = draw_inputs(inputs_rng, players);
        for (const scheduled& s : schedule) {
            if (s.tick != record.tick) continue;
            if (s.join) {
                record.joins.emplace_back(s.owner);
            } else if (auto it = players.find(world::player_id{s.owner}); it != players.end()) {
                record.leaves.push_back(it->second.body_id);
                players.erase(it);
            }
        }
        // A leaving player's input of this tick is dropped, as the server drops it.
        std::erase_if(record.inputs, [&](const world::body_input& in) {
            for (const world::body_id id : record.leaves) {
                if (id == in.body_id) return true;
            }
            return false;
        });
        const std::vector<world::body_id> spawned = match::apply_tick(w, record);
        for (size_t i = 0; i < spawned.size(); ++i) {
            if (spawned[i]) players[record.joins[i]].body_id = spawned[i];
        }
        uint64_t hash = w.hash();
        out.hashes.push_back(hash);
        if (script.alter_hash_at == w.tick()) hash ^= 1;
        if (status s = rec.record_tick(record, hash); !s) return r::failure(s.error);
    }
    out.final_tick = w.tick();
    out.final_hash = w.hash();
    if (script.finish) {
        if (status s = rec.finish(out.final_tick, out.final_hash); !s) return r::failure(s.error);
    }
    return r::success(std::move(out));
}

}  // namespace arena::replay::testing
