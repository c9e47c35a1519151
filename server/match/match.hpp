#pragma once
// The match: the world, its players and their input buffers, one tick at a time, and the
// snapshot fan-out. It knows clients only as connections a transport handed it, and what they
// may send only through its admission rules (admission.hpp); it logs through a logger it was
// handed and never reads a clock: the server's tick loop calls tick() at the fixed rate, and
// every duration here is counted in ticks.
//
// A transport's whole contract: connect() each new connection, receive() each verified
// message, reject() what it could not read or send, disconnect() a connection that ended by
// itself, shut_down() at the end; and implement `connection` for the match to talk back.
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "protocol/messages.hpp"
#include "protocol/snapshot.hpp"
#include "server/match/admission.hpp"
#include "server/match/close_cause.hpp"
#include "server/match/connection.hpp"
#include "server/match/figures.hpp"
#include "server/match/game_feed.hpp"
#include "server/match/input_buffer.hpp"
#include "server/match/logger.hpp"
#include "server/match/outbox.hpp"
#include "server/match/snapshot_fanout.hpp"
#include "server/match/tick_record.hpp"
#include "server/world/world.hpp"

namespace arena::match {

struct match_config {
    uint16_t tick_rate = 60;       // ticks per second
    uint16_t snapshot_rate = 20;   // snapshots per second: a divisor of tick_rate (the Welcome tells it)
    admission_limits admission{};  // players, spectators, connections, time-outs, message limits
    uint32_t input_buffer = 8;     // inputs waiting per player; more drop the oldest
    std::string preset;            // name sent in Welcome ("" for a config file)
    std::string match_id;          // this match's id in its process (Welcome.match)
    std::string mode;              // the mode it plays (Welcome.mode; server/config/modes.hpp)
    uint64_t seed = 1;
    double reconnect_grace_s = 10;  // a dropped player's body waits this long for it
    float view_radius = 0;          // m: snapshots hold the bodies this near a player's; 0 = all
    uint32_t delta_history = 32;    // snapshots kept as delta baselines per client (1.6 s at 20 Hz)
    uint32_t score_limit = 0;       // the match is over when a player's score reaches it; 0: no limit
    // Lag compensation (docs/LAG_COMPENSATION.md): an input's shots are judged against the
    // world as its player saw it, up to this far back (and never more than world::max_rewind);
    // 0 turns it off.
    uint32_t lag_compensation_ms = 250;
};

struct match_counters {
    uint64_t joins = 0;
    uint64_t leaves = 0;
    uint64_t snapshots_sent = 0;
    uint64_t input_underruns = 0;
    uint64_t input_overflows = 0;
    uint64_t inputs_received = 0;
    uint64_t stale_inputs = 0;      // sequence not above the last received: ignored
    uint64_t inputs_recovered = 0;  // taken from a later Input's `earlier`: its own datagram was lost or late
    uint64_t inputs_lost = 0;       // sequences skipped: neither their Input nor a later one's `earlier` came
    uint64_t snapshot_bytes = 0;    // the last snapshot frame built, bytes
    uint64_t reconnects = 0;
    uint64_t takeovers = 0;
    uint32_t players_peak = 0;
    std::map<protocol::RejectCode, uint64_t> rejects;  // Rejects sent, by code
    std::map<std::string, uint64_t> closes;            // connections ended, by close_cause::key()
    fanout_counters snapshots;                         // frames by kind, and the delta frames' bytes and bodies
    uint64_t ticks = 0;                                // world steps so far
    uint64_t players = 0;                              // players in the match now with a live connection
    uint64_t players_in_grace = 0;                     // dropped players whose bodies wait for them
    uint64_t max_players = 0;                          // the limit
    uint64_t spectators = 0;                           // spectators watching now (no body, no score line)
    uint64_t shots = 0;                                // the game rules' scoreboard, summed: bullets fired
    uint64_t hits = 0;                                 // shots that hit a rock or a ship
    uint64_t kills = 0;                                // ships destroyed by another player's bullet
};

// Every figure of `c`, to `out`: the one place that names them for the stats and /metrics.
void report(const match_counters& c, figure_sink& out);

class match;

// A player of a match, connected or waiting in the reconnect grace.
struct match_player {
    // First what an Input touches (the connection, the input ring, the acknowledgement at the
    // head of snapshots): the first two cache lines, which the transport fetches ahead.
    connection* who = nullptr;  // nullptr while disconnected within the grace period
    input_buffer inputs;
    snapshot_client snapshots;  // delta baselines and the client's acknowledgement
    world::body_id body_id;     // none (0) until spawned
    uint32_t game_sent = 0;     // BodyState clients: the game's version the last snapshot brought (game_feed)
    uint32_t events_from = 0;   // the game's version at connection: the events it hears come after it
    uint32_t disconnected_at_tick = 0;
    std::string name;
    std::string identity;
};

// What a match keeps of a connection it holds; the connection points to it (connection::record).
struct client_record {
    // First what an Input reads (the first two cache lines, which the transport fetches ahead).
    const match* owner = nullptr;    // the match that holds the connection
    match_player* player = nullptr;  // the player it plays, while the match has it (not a spectator's)
    client_standing standing;
    world::player_id player_id;    // none (0) until the Hello is accepted
    bool connection_gone = false;  // the connection ended before the match forgot it (~connection)
    uint64_t serial = 0;           // order of connection: a fixed order for what is done to every client
    std::string address;           // the peer's address without its port
};

class match {
public:
    // `check_token` verifies signed join tokens (unset: an open server, see admission.hpp).
    match(const match_config& config, const world::world_config& world_config, logger log = {},
          token_check check_token = {});
    // Its connections' records point into it: it neither moves nor copies, and when it ends it
    // clears them in the connections still there.
    ~match();
    match(const match&) = delete;
    match& operator=(const match&) = delete;

    // A new connection. False: it was refused (its Reject is on its way) and is forgotten.
    bool connect(connection& c);
    // A verified message from `c` that arrived at `arrival_ns` (the transport's steady clock,
    // in nanoseconds: rates are measured in real time, so that a stall of the server does not
    // look like a flood). False: the connection is over and should close once its output is
    // flushed (a refusal was sent, or the client said Bye).
    // `held_ns` (≥ 0, or -1: not measured): how long the bytes waited before the transport read
    // them (TCP: since the kernel received them); a Pong tells the client, so that it can tell
    // the network's round trip from the server's wait for its next read.
    [[nodiscard]] bool receive(connection& c, const protocol::Message& message, int64_t arrival_ns,
                               int64_t held_ns = -1);
    // The same, for a transport without a clock (tests, simulations): the message arrived at
    // the current tick's time, tick × the tick period.
    [[nodiscard]] bool receive(connection& c, const protocol::Message& message);
    // Ends `c` with this Reject: bytes its transport could not frame or verify, output that
    // does not drain.
    void reject(connection& c, const rejection& why);
    // Lets a connection that has not said Hello go to another match of the process (the
    // host's match registry moves it on its Hello): forgotten here without a word, a close or a
    // count; the other match connects it. Nothing for a connection past its Hello.
    void release(connection& c);
    // Whether `c` is a connection of this match that has not said Hello yet.
    [[nodiscard]] bool waiting_for_hello(const connection& c) const;
    // `c` ended by itself (end of stream, a socket error): a joined player's body waits
    // reconnect_grace_s for the same identity.
    void disconnect(connection& c, const close_cause& cause);
    // No new players from now on, and Bye(reason) to every connection; under rules that keep
    // score the Bye carries the result: the winner and the final scoreboard.
    void shut_down(std::string_view reason);
    // True once a player's score reached match_config::score_limit or the rules ended the match
    // (rules::finished: a clock ran out): the server shuts down, or ends this match.
    [[nodiscard]] bool over() const { return over_; }
    // The refusal `hello` would meet from the Hello and capacity rules now (admission's
    // admit_hello, then admit_join or admit_spectator), without joining: how a process with
    // many matches picks one with a seat. A reconnection or takeover always has its seat.
    // `here` false: the Hello's own rules only, not whether its token is good for this match
    // (the Hello is on its way to another).
    [[nodiscard]] std::optional<rejection> seat_refusal(const protocol::hello_msg& hello, bool here = true) const;
    // The result the last Bye carries (over is false under rules that keep no score).
    [[nodiscard]] protocol::match_result result() const;

    // One world step: joins, leaves, one input per player, the step, then the snapshot if due;
    // then what time alone refuses (a Hello that never came).
    void tick();
    // While set, what tick() says to connections (Welcomes, Rejects, snapshots) is kept in `out`
    // in order instead of sent: a tick on a worker thread, whose output the host delivers on the
    // io thread (outbox.hpp). Null: sent at once. Only tick() may run while it is set.
    void defer_output(outbox* out) { outbox_ = out; }

    // Called after every step with what the tick changed and the world's hash (recording).
    std::function<void(const tick_record&, uint64_t)> on_tick;

    const world::world& state() const { return world_; }
    // The game rules this match plays by (the world config's `rules`).
    const rules::rules& game_rules() const { return *rules_; }
    // The scoreboard, in player id order, with each player's name (empty under sandbox rules).
    struct named_score {
        std::string name;
        rules::score_line line;
    };
    std::vector<named_score> scoreboard() const;
    // What a body is for drawing (protocol BodyShape.kind: ship, rock...); 0, a plain body,
    // unless a game's rules tag it; a change reaches every client that holds the body (body_kinds.hpp).
    void set_body_kind(uint32_t body_id, uint8_t kind) { kinds_.set(body_id, kind); }
    uint8_t body_kind(uint32_t body_id) const { return kinds_.of(body_id); }
    // The Welcome a player with this id and body would get now (statics included).
    protocol::welcome_info welcome_for(uint32_t player_id, uint32_t body_id) const;
    const match_config& config() const { return config_; }
    const admission& rules() const { return admission_; }
    const std::string& world_config_json() const { return world_config_json_; }
    // Totals so far, live players' input buffers included.
    match_counters counters() const;
    size_t player_count() const { return players_.size(); }  // live and in the reconnect grace
    size_t live_player_count() const { return players_.size() - players_in_grace(); }
    size_t players_in_grace() const;  // dropped players whose bodies wait for them
    // The ids of the players with a live connection, in increasing order.
    std::vector<uint32_t> live_player_ids() const;
    size_t connection_count() const { return clients_.size(); }
    size_t spectator_count() const { return spectators_.size(); }
    // The player `c` plays, or the id its spectator was welcomed with (0: none yet, or not a
    // connection of this match).
    uint32_t player_of(const connection& c) const;
    bool draining() const { return draining_; }

private:
    using player = match_player;
    // A client that watches: it has no body, no input buffer, no score line and no identity
    // (admission.hpp); it gets the Welcome, the snapshots and the game like a player, and the
    // last Bye. Its fields that the snapshots need are named as the player's.
    struct spectator {
        connection* who = nullptr;
        std::string name;
        snapshot_client snapshots;
        uint32_t game_sent = 0;    // the game's version the last snapshot brought (game_feed)
        uint32_t events_from = 0;  // the game's version at connection: the events it hears come after it
    };
    using client = client_record;
    using client_map = std::unordered_map<const connection*, client>;
    using player_map = std::map<world::player_id, player>;        // by player id: a deterministic order
    using spectator_map = std::map<world::player_id, spectator>;  // by the id of its Welcome

    bool on_hello(connection& c, client& cl, const protocol::hello_msg& hello);
    // A Hello that passed with spectator set: welcomed at once, it has no body to wait for.
    bool on_spectator_hello(connection& c, client& cl, const admitted_hello& admitted);
    bool on_input(connection& c, client& cl, const protocol::input_msg& input, int64_t arrival_ns);
    // The waiting connection that gives its handshake slot up to a new one (not `newcomer`).
    connection* oldest_waiting_of_busiest_address(const connection* newcomer) const;
    // A new player needs a slot held by a body in the reconnect grace: the oldest one goes.
    void give_up_oldest_in_grace();
    player_map::iterator find_identity(const std::string& identity);
    player_map::const_iterator find_identity(const std::string& identity) const;
    // Forgets `it`: counts why it closed, and its player leaves or waits for a reconnection.
    void forget(client_map::iterator it, const close_cause& cause);
    // The connection of `entry` no longer points to its record, unless it is gone already
    // (~connection marked the record): nothing is written to a connection that ended first.
    static void unlink(const client_map::value_type& entry) {
        if (!entry.second.connection_gone) entry.first->record = nullptr;
    }
    void leave(player_map::iterator it, const close_cause& cause);
    void spawn_pending(const std::vector<world::player_id>& owners, const std::vector<world::body_id>& bodies);
    void send_welcome(world::player_id id, player& p);
    // Any client's Welcome: its shape tracker starts after the bodies it describes.
    void send_welcome(connection& c, snapshot_client& snapshots, const protocol::welcome_info& welcome);
    void remove_player(player_map::iterator it, std::string_view reason);
    void expire_disconnected();
    void check_clients();   // admission's rules over time, in connection order
    void send_snapshots();  // to the clients whose snapshot is due this tick
    // The rules' kind of each body that appeared or was retagged since the last tick, and a new
    // bullet's origin.
    void tag_new_bodies();
    // The rewind (1/256 ticks) of an input made from the view moment `view` (1/256 ticks, 0 =
    // not told), applied this tick: clamped to [0, the cap]; a view of the future gets 0.
    uint16_t rewind_of(uint64_t view) const;
    void record_origin(uint32_t body_id, const rules::shot_record& shot);
    // `r` is a player or a spectator: what it sees is the view around `own`, or with none
    // (a spectator) the whole world; `ack` is its last input consumed.
    template <class Reader>
    void send_snapshot(Reader& r, world::body_id own, uint32_t ack);
    // Into game_list_: what `r`'s snapshot at this tick carries of the game.
    template <class Reader>
    const protocol::game_list* game_for(Reader& r, uint32_t& through);
    uint32_t snapshot_interval() const;
    // Delta clients whose player ids are the same after dividing by this get their snapshots on
    // the same tick (send_snapshots): a match of up to this many players shares one tick's work,
    // and a big one is still spread over the interval within a group's size.
    static constexpr uint32_t snapshot_group = 16;
    tick_ring baseline_ring() const { return {config_.delta_history, snapshot_interval()}; }

    match_config config_;
    logger log_;
    admission admission_;
    world::world world_;
    std::unique_ptr<rules::rules> rules_;            // set up on world_, before anything else touches it
    protocol::game_manifest manifest_;               // what the rules declare of the game, asked once
    std::map<world::player_id, std::string> names_;  // every player who joined, for the scoreboard after they left
    std::string world_config_json_;
    uint64_t world_config_hash_;
    client_map clients_;
    uint64_t next_serial_ = 1;
    size_t awaiting_hello_ = 0;  // clients that have not said Hello
    player_map players_;
    spectator_map spectators_;
    std::vector<world::player_id> pending_joins_;     // players whose body spawns next tick
    std::vector<world::body_id> pending_leaves_;      // bodies to remove next tick
    std::vector<world::player_id> pending_welcomes_;  // reconnected players, welcomed after the next tick
    uint32_t next_player_id_ = 1;
    bool draining_ = false;
    snapshot_fanout fanout_;
    body_kinds kinds_;
    shot_origins origins_;              // the live bullets' (tag_new_bodies)
    std::vector<uint32_t> retagged_;    // the bodies the rules retagged this tick
    uint32_t kinds_asked_below_ = 0;    // the rules were asked the kind of every body id below this
    match_counters counters_;           // departed players' buffers folded in on leave
    game_feed game_;                    // lines, names and events for the players (rules with state)
    protocol::game_list game_list_;     // one client's, being sent
    protocol::game_list shared_game_;   // the shared frame's
    uint32_t shared_game_sent_ = 0;     // the game's version the newest shared frame brought
    uint32_t shared_game_through_ = 0;  // this tick's shared frame's
    bool over_ = false;
    outbox* outbox_ = nullptr;  // defer_output()'s
};

}  // namespace arena::match
