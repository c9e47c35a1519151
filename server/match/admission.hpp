#pragma once
// Every rule about what a client may send, and when, in one place: how many connections and
// handshakes at once, message order, the Hello (version, name and token limits, the token's
// identity), reconnection and takeover, capacity (players and spectators), and inputs (order,
// rate, finite numbers; none from a spectator).
// Each rule is checked once, here, at the boundary, and a refusal is a typed `rejection` (the
// RejectCode the client reads, and a detail). The match acts on the verdicts; transports only
// frame and verify bytes (protocol/) and hand the messages over.
//
// Where a new rule goes: a limit on connections in admit_connection(), on a message kind in
// admit_message(), on the Hello in admit_hello(), on who may take which player in
// admit_join() (admit_spectator() for those who watch), on inputs in admit_input(), on a client's behaviour over time
// in check_on_tick(). What a rule must remember about one client lives in client_standing.
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "protocol/decode.hpp"
#include "protocol/framing.hpp"
#include "server/match/close_cause.hpp"
#include "server/match/input_buffer.hpp"
#include "server/match/token_bucket.hpp"
#include "server/world/input.hpp"
#include "server/world/result.hpp"

namespace arena::match {

// The limits of who may connect and send what: each lives here and only here, the server's
// flags set them (server/cli/server_flags.cpp), the match and the transports read them. Every
// duration is a std::chrono duration; the match counts the time-outs in its ticks
// (admission's constructor converts them once).
struct admission_limits {
    uint32_t max_players = 64;            // players at once
    uint32_t max_spectators = 16;         // spectators at once (Hello.spectator), besides the players; 0: none
    uint32_t max_connections = 0;         // open connections at once; 0: 2 × max_players + max_spectators + 16
    uint32_t max_pending_handshakes = 0;  // connections that have not sent Hello yet; 0: see pending_limit()
    std::chrono::nanoseconds handshake_timeout =
        std::chrono::seconds(5);  // a new connection has this long to send Hello
    std::chrono::nanoseconds idle_timeout =
        std::chrono::seconds(5);         // a joined client may go this long without an Input; 0: never
    uint32_t max_name_bytes = 64;        // Hello.name, bytes
    uint32_t max_token_bytes = 1024;     // Hello.token, bytes
    uint32_t max_match_bytes = 64;       // Hello.match and Hello.mode, bytes each
    uint32_t max_inputs_per_second = 0;  // 0: 2 × tick_rate + 10
    // Inputs at the limit a client may send at once, as the time they span: what the kernel
    // holds after the server (or the network) stood still this long arrives together and must
    // not be refused.
    std::chrono::nanoseconds input_burst = std::chrono::seconds(5);
    uint32_t max_pings_per_second = 5;  // a client pings about once a second
    uint32_t ping_burst = 20;           // Pings at once
};

// What a signed token says: the player name it was minted for and the match it is good for
// ("": any), or why it is refused ("token expired"). Checking a signature needs a secret and
// the wall clock, so the caller hands a checker in; without one the server is open and a token
// is the client's own opaque key.
struct signed_token {
    std::string name;
    std::string match;
};
using token_check = std::function<result<signed_token>(std::string_view token)>;

// Where one client stands with admission; the match keeps one per connection.
struct client_standing {
    enum class stage : uint8_t { awaiting_hello, joined };
    stage at = stage::awaiting_hello;
    uint32_t connected_tick = 0;   // the world's tick when the connection was handed over
    bool spectator = false;        // joined to watch: sends no Input; its Pings keep it from the idle timeout
    uint32_t last_input_tick = 0;  // the tick of the last Input (a spectator's: Ping), or of the Hello: idle since
    uint32_t last_sequence = 0;    // newest Input.sequence taken; older ones are stale
    token_bucket inputs;           // the input rate, in the transport's arrival times
    token_bucket pings;            // the Ping rate, likewise
};

// A message that passed the order and decoding rules, as its typed content.
struct hello_message {
    protocol::hello_msg hello;
};
struct input_message {
    protocol::input_msg input;
};
struct ping_message {
    uint64_t client_time = 0;
};
struct bye_message {
    std::string reason;  // "(unreadable)" when the Bye did not decode: the client leaves anyway
};
using admitted_message = std::variant<rejection, hello_message, input_message, ping_message, bye_message>;

// A Hello that passed: who the player (or spectator) is.
struct admitted_hello {
    std::string name;           // the signed name with a token secret, else the Hello's name
    std::string identity;       // the key a reconnection is matched by; empty: none (cannot reconnect)
    bool spectator = false;     // Hello.spectator: joins without a body
    std::string token_match{};  // the one match its signed token is good for; "": any
};

// How a Hello joins, given the player already holding its identity, if any.
enum class join_kind : uint8_t {
    new_player,  // a new player id and body
    reconnect,   // the same player, whose connection dropped within the grace period
    takeover,    // the same player, still connected elsewhere: the old connection gets Bye
};

// An Input that passed: the world's input, or nothing to do (a stale sequence).
struct admitted_input {
    bool stale = false;  // sequence not above the last taken: ignored, not refused
    world::player_input input{};
    uint64_t view = 0;  // Input.view_tick and view_fraction in 1/256 ticks; 0 = not told
    // Earlier inputs (Input.earlier) newer than the last taken, oldest first: each goes to the
    // buffer before `input`, so a lost datagram's input arrives with the next one.
    std::vector<sequenced_input> recovered;
    // Sequences between the last taken and this one that neither came nor were repeated in
    // `earlier`: inputs the world never gets (a gap the redundant inputs did not close).
    uint64_t lost = 0;
};

class admission {
public:
    // `tick_rate`: the match's ticks per second, in which the time-outs are counted.
    admission(const admission_limits& limits, uint16_t tick_rate, token_check check_token = {});

    // A new connection, when `open` are open (this one included) and `awaiting_hello` of
    // them (this one included) have not said Hello. A new connection always gets in while the
    // server has room for players: when the handshake slots (or the connections) are all taken,
    // the verdict is that one waiting connection gives its slot up (make_room); the match picks
    // the oldest of the source address that holds the most (so one address cannot push the
    // others out) and closes it with waiting_evicted(). Only a server whose connections are all
    // players refuses, as server_full.
    enum class connection_verdict : uint8_t { admit, make_room };
    [[nodiscard]] std::variant<connection_verdict, rejection> admit_connection(size_t open,
                                                                               size_t awaiting_hello) const;
    [[nodiscard]] static rejection waiting_evicted();
    // Bytes a transport could not frame, or a frame that failed verification.
    [[nodiscard]] static rejection unreadable(const protocol::frame_reader& reader);
    [[nodiscard]] static rejection unverified(std::string_view error);

    // A verified message from a client: in order for its stage, and decoded.
    [[nodiscard]] admitted_message admit_message(const client_standing& client, const protocol::Message& message) const;
    // The Hello's own rules: the server is not draining, the version, the name and token
    // limits, and the token's identity. A spectator passes the same checks (a server with a
    // token secret lets only holders of a good token watch) but holds no identity: it never
    // takes a player over nor is taken over, so watching one's own match from a second
    // connection, under the same name or token, does not end the game's connection.
    [[nodiscard]] std::variant<admitted_hello, rejection> admit_hello(const protocol::hello_msg& hello,
                                                                      bool draining) const;
    // Whether the player may join: `same_identity_connected` is unset when no player holds the
    // identity, else whether that player is still connected. `live_players` counts the players
    // with a connection: bodies waiting in the reconnect grace do not keep a new player out
    // (the match gives the oldest of them up to make room).
    [[nodiscard]] std::variant<join_kind, rejection> admit_join(std::optional<bool> same_identity_connected,
                                                                size_t live_players) const;
    // Whether a spectator may join while `spectators` watch: spectators have a cap of their own
    // (max_spectators) and take no player's slot; 0 admits none (server_full, as a full match
    // refuses a player).
    [[nodiscard]] std::optional<rejection> admit_spectator(size_t spectators) const;
    // Whether a Hello admitted by admit_hello() may join the match `match_id`: its signed token
    // names that match, or none.
    [[nodiscard]] static std::optional<rejection> admit_token_match(const admitted_hello& admitted,
                                                                    std::string_view match_id);
    // An Input from a joined client that arrived at `arrival_ns` (the transport's clock, in
    // nanoseconds): the rate, finite numbers, and the sequence order. Updates `client` (the
    // rate bucket, the last sequence, the idle time) when it passes.
    [[nodiscard]] std::variant<admitted_input, rejection> admit_input(client_standing& client,
                                                                      const protocol::input_msg& input,
                                                                      int64_t arrival_ns, uint32_t tick) const;
    // A Ping from a joined client at `arrival_ns`, at `tick`: within the ping rate, or refused
    // (ping_limit) before its Pongs could fill the connection's output. A spectator sends no
    // Input, so a Ping is what tells that it is still there: it restarts its idle time.
    [[nodiscard]] std::optional<rejection> admit_ping(client_standing& client, int64_t arrival_ns, uint32_t tick) const;
    // Once per tick, after the step, for each client: what time alone refuses (a Hello that
    // never came, a joined client that stopped sending Inputs).
    [[nodiscard]] std::optional<rejection> check_on_tick(const client_standing& client, uint32_t tick) const;

    [[nodiscard]] uint32_t input_limit() const;
    [[nodiscard]] uint32_t connection_limit() const;
    // Connections waiting to say Hello at once: max_pending_handshakes, or when 0 enough for
    // every free player slot to fill at once (max_players + 16, at least 64): 200 bots that
    // connect together to a 256-player server all get in.
    [[nodiscard]] uint32_t pending_limit() const;
    [[nodiscard]] const admission_limits& limits() const { return limits_; }

private:
    admission_limits limits_;
    uint16_t tick_rate_;
    uint32_t handshake_timeout_ticks_;  // limits_'s time-outs in ticks (at least 1; idle: 0 is never)
    uint32_t idle_timeout_ticks_;
    token_check check_token_;
};

}  // namespace arena::match
