#pragma once
// The match: the world, its players and their input buffers, one tick at a time, and the
// snapshot fan-out. It knows clients only as connections it was handed, logs through a logger
// it was handed and never reads a clock: the server's tick loop calls tick() at the fixed rate.
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "protocol/messages.hpp"
#include "protocol/snapshot.hpp"
#include "server/match/connection.hpp"
#include "server/match/input_buffer.hpp"
#include "server/match/logger.hpp"
#include "server/match/snapshot_fanout.hpp"
#include "server/match/tick_record.hpp"
#include "server/world/world.hpp"

namespace arena::match {

struct match_config {
    uint16_t tick_rate = 60;      // ticks per second
    uint16_t snapshot_rate = 20;  // snapshots per second (a divisor of tick_rate works best)
    uint32_t max_players = 64;
    uint32_t input_buffer = 8;           // inputs waiting per player; more drop the oldest
    uint32_t max_inputs_per_second = 0;  // 0: 2 × tick_rate + 10
    uint32_t max_name_bytes = 64;
    uint32_t max_token_bytes = 1024;
    std::string preset;  // name sent in Welcome ("" for a config file)
    uint64_t seed = 1;
    double reconnect_grace_s = 10;  // a dropped player's body waits this long for it
    float view_radius = 0;          // m: snapshots hold the bodies this near a player's; 0 = all
    uint32_t delta_history = 32;    // snapshots kept as delta baselines per client (1.6 s at 20 Hz)
};

struct rejection {
    protocol::RejectCode code;
    std::string reason;
};

struct match_counters {
    uint64_t joins = 0;
    uint64_t leaves = 0;
    uint64_t snapshots_sent = 0;
    uint64_t input_underruns = 0;
    uint64_t input_overflows = 0;
    uint64_t inputs_received = 0;
    uint64_t stale_inputs = 0;    // sequence not above the last received: ignored
    uint64_t snapshot_bytes = 0;  // the last snapshot frame built, bytes
    uint64_t reconnects = 0;
    uint64_t takeovers = 0;
    uint32_t players_peak = 0;
    fanout_counters snapshots;  // frames by kind, and the delta frames' bytes and bodies
};

class match {
public:
    match(const match_config& config, const world::world_config& world_config, logger log = {});

    // A Hello: the player id, or why not. The body spawns and Welcome is sent at the next tick.
    // `identity` (from a verified token, or the client's opaque token; empty: none) lets a
    // player whose connection dropped come back to the same player and body within the grace
    // period; a second connection with a connected identity takes the player over.
    std::variant<uint32_t, rejection> join(connection& who, const protocol::hello_msg& hello,
                                           const std::string& identity = {});
    // `who` is gone. After a Bye or a refusal its body goes at the next tick; after a lost
    // connection the body waits reconnect_grace_s for the same identity. A call from a
    // connection that no longer holds the player (it was taken over) changes nothing.
    void leave(uint32_t player_id, const connection& who, std::string_view reason, bool connection_lost = false);
    // An Input from a joined player: buffered for the world, or why it ends the connection.
    std::optional<rejection> receive_input(uint32_t player_id, const protocol::input_msg& input);

    // One world step: joins, leaves, one input per player, the step, then the snapshot if due.
    void tick();

    // Called after every step with what the tick changed and the world's hash (recording).
    std::function<void(const tick_record&, uint64_t)> on_tick;

    const world::world& state() const { return world_; }
    const match_config& config() const { return config_; }
    const std::string& world_config_json() const { return world_config_json_; }
    // Totals so far, live players' input buffers included.
    match_counters counters() const;
    size_t player_count() const { return players_.size(); }

private:
    struct player {
        connection* who = nullptr;  // nullptr while disconnected within the grace period
        std::string name;
        std::string identity;
        uint32_t disconnected_at_tick = 0;
        uint32_t body_id = 0;  // 0 until spawned
        input_buffer inputs;
        uint32_t last_received_sequence = 0;
        uint32_t inputs_this_window = 0;
        snapshot_client snapshots;  // delta baselines and the client's acknowledgement
    };

    void spawn_pending(const std::vector<uint32_t>& owners, const std::vector<uint32_t>& bodies);
    void send_welcome(uint32_t player_id, const player& p);
    void remove_player(std::map<uint32_t, player>::iterator it, std::string_view reason);
    void expire_disconnected();
    void send_snapshots();  // to the clients whose snapshot is due this tick
    uint32_t input_limit() const;
    uint32_t snapshot_interval() const;
    tick_ring baseline_ring() const { return {config_.delta_history, snapshot_interval()}; }

    match_config config_;
    logger log_;
    world::world world_;
    std::string world_config_json_;
    uint64_t world_config_hash_;
    std::map<uint32_t, player> players_;      // by player id: a deterministic order
    std::vector<uint32_t> pending_joins_;     // player ids whose body spawns next tick
    std::vector<uint32_t> pending_leaves_;    // body ids to remove next tick
    std::vector<uint32_t> pending_welcomes_;  // reconnected players, welcomed after the next tick
    uint32_t next_player_id_ = 1;
    snapshot_fanout fanout_;
    match_counters counters_;  // departed players' buffers folded in on leave
};

}  // namespace arena::match
