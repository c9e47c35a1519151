#pragma once
// The matches this process hosts. The default match lives as long as the process and takes
// every client that names neither a match nor a mode, as a server of one match always did;
// a Hello that names a match (Hello.match) joins it, one that names a mode (Hello.mode) joins
// the fullest open match of that mode with a seat or creates one (join-or-create), and the
// lobby creates them on request. A match created on demand ends when its rules end it, when
// its mode's duration is up, when it has been empty for the empty-match time, or when it
// throws: it says Bye to its clients, its slot is freed, and its neighbours never notice.
//
// A connection is the default match's until its Hello moves it (connection::match_key); the
// intake and the transports ask here for a connection's match and never hold one. No sockets
// and no clock: the host hands the clock in where a tick is timed.
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "server/config/modes.hpp"
#include "server/host/tick_pool.hpp"
#include "server/match/match.hpp"

namespace arena::host {

inline constexpr std::string_view default_match_id = "default";

// One hosted match and what the process knows of it.
struct hosted_match {
    uint64_t key = 0;        // connection::match_key; 0 is the default match
    std::string id;          // its public id (Hello.match, the lobby's URLs): unguessable but for the default
    std::string mode;        // the mode it plays
    bool on_demand = false;  // created by a Hello's mode or the lobby: it ends when empty
    bool listed = true;      // false: private, left out of the lobby's list (its id is the invitation)
    int64_t created_unix_ms = 0;
    std::string creator;         // the address whose Hello or lobby request created it ("": the process)
    uint32_t empty_ticks = 0;    // ticks since it last had a client
    uint32_t end_tick = 0;       // its mode's duration ends it at this tick; 0: no limit
    uint64_t ticks_late = 0;     // ticks it ran more than a tick interval after they fell due
    uint64_t ticks_dropped = 0;  // ticks the process fell too far behind to run (tick_clock)
    std::unique_ptr<match::match> game;
};

// What a match that ran leaves behind, for the stats (--stats-json's "matches").
struct match_summary {
    std::string id;
    std::string mode;
    std::string ended;  // why it ended; "" while it runs
    match::match_counters counters;
    std::vector<match::match::named_score> scoreboard;
    uint32_t winner = 0;
    uint64_t ticks_late = 0;
    uint64_t ticks_dropped = 0;
};

struct registry_options {
    match::match_config base;              // every match's config; its mode's capacity overrides max_players
    std::vector<config::mode> modes;       // what Hello.mode and the lobby may name
    std::string default_mode;              // the default match's mode (one of modes)
    uint32_t max_matches = 1;              // matches at once, the default one included
    uint32_t empty_match_ticks = 30 * 60;  // a match created on demand ends after this many ticks empty
    // Matches without a client one address may have created (by the lobby, or by a Hello that
    // then left): one address cannot take the slots with empty matches.
    uint32_t max_matches_per_address = 4;
    // At max_matches, a match created on demand that has been empty this long gives its slot up
    // to a new one: creating and leaving matches cannot starve the joins that need one.
    uint32_t reclaim_empty_ticks = 5 * 60;
    // Threads that tick the matches, the calling one included (--threads); 1: the caller alone.
    unsigned threads = 1;
    // The wall clock, ms since the epoch, for a match's "created" (unset: 0, as in tests).
    std::function<int64_t()> wall_clock_ms;
};

// A registry of one match that plays `world` under `config` (mode "custom"): a test's, a tool's.
registry_options one_match(const match::match_config& config, const world::world_config& world);

class match_registry {
public:
    // `log` receives every match's lines (a match created on demand prefixes its id);
    // `check_token` verifies signed join tokens for every match. Throws when the default
    // match cannot start (a bad config: the process should not either).
    match_registry(registry_options options, match::logger::sink log = {}, match::token_check check_token = {});

    match::match& default_match() { return *default_->game; }
    const match::match& default_match() const { return *default_->game; }
    // The match with this public id, or nullptr.
    hosted_match* find(std::string_view id);
    // The match `c` belongs to. A connection whose match has ended is routed to the default
    // match, which knows it not and so ignores what it sends.
    match::match& match_of(const match::connection& c);
    // `c`'s Hello, before its current match reads it: the match that should take it. With
    // Hello.match or Hello.mode set, `c` is moved there (released by its current match,
    // connected to the new one); nullptr: refused, its Reject on its way.
    match::match* route_hello(match::connection& c, const protocol::hello_msg& hello);
    // A new match of `mode`, listed or private, created for `creator` (an address; "": the
    // process itself): the entry, or why not (mode_unknown, no_room_for_match: the process or
    // the address holds as many as it may, or a config that does not start). At max_matches
    // it first ends the match created on demand that has been empty longest, if that is at
    // least reclaim_empty_ticks.
    // `id`: the match's id when the caller names it (an Agones allocation's arena.dev/match:
    // 1 to 64 of [A-Za-z0-9_-], not in use); "": a new random one.
    std::variant<hosted_match*, match::rejection> create(std::string_view mode, bool listed,
                                                         std::string_view creator = {}, std::string_view id = {});

    // One tick of every match, each timed with `now_ns` and reported to `ticked`; then the
    // matches created on demand that ended are said Bye to and forgotten. With threads > 1 the
    // matches tick at once on the pool, each on one thread, their output kept (outbox.hpp) and
    // delivered on the calling thread in the order the matches were created; `now_ns` must be
    // safe to call from any thread. An exception from a match's tick ends that match alone (the
    // default match's is rethrown: the process cannot go on without it).
    void tick_all(const std::function<int64_t()>& now_ns,
                  const std::function<void(const hosted_match&, int64_t spent_ns)>& ticked = {});
    // The process fell behind: `late` of the ticks about to run are catching up, and `dropped`
    // were given up (tick_clock). Every match running counts them: its own ticks were late.
    void count_late_ticks(uint64_t late, uint64_t dropped);
    // Told of every match as it starts (those running now at once) and as it ends, before it
    // is forgotten (its last tick done, its Bye sent): a recording per match.
    void observe(std::function<void(hosted_match&)> started,
                 std::function<void(hosted_match&, const std::string& why)> ending);

    // Why the default match is over ("" while it plays): its rules ended it, or its mode's
    // duration is up. The process then shuts down.
    std::string default_match_over() const;
    // Bye(reason) to every client of every match: the process is shutting down.
    void shut_down(std::string_view reason);

    // The matches now, in creation order.
    const std::map<uint64_t, hosted_match>& matches() const { return matches_; }
    size_t size() const { return matches_.size(); }
    const registry_options& options() const { return options_; }
    // The matches that ran: those running (the default one first), then those that ended (the
    // newest max_summaries of them).
    std::vector<match_summary> summaries() const;
    // Matches created, whole run, the default one included.
    uint64_t created() const { return created_; }

    static constexpr size_t max_summaries = 1000;

private:
    // Creates the match without checking the limit; throws what a bad config throws.
    hosted_match& start(const config::mode& mode, bool on_demand, bool listed, std::string id = {});
    // The fullest open, listed match of `mode` in which `hello` has a seat; nullptr: none.
    hosted_match* fullest_with_seat(std::string_view mode, const protocol::hello_msg& hello);
    void end(std::map<uint64_t, hosted_match>::iterator it, const std::string& why);
    // Ends the longest-empty match created on demand, if it has been empty long enough.
    bool reclaim_empty();
    std::string new_id();
    match_summary summary_of(const hosted_match& m, std::string ended) const;

    registry_options options_;
    match::logger::sink log_;
    match::token_check check_token_;
    std::map<uint64_t, hosted_match> matches_;  // by key: creation order
    // The same matches in one array, by key: every input finds its match here (match_of) and
    // every tick walks it, without chasing the map's nodes through memory.
    struct indexed_match {
        uint64_t key;
        hosted_match* hosted;
        match::match* game;
    };
    std::vector<indexed_match> index_;
    hosted_match* default_ = nullptr;
    uint64_t next_key_ = 0;
    uint64_t created_ = 0;
    std::vector<match_summary> ended_;
    std::unique_ptr<tick_pool> pool_;  // threads > 1
    std::function<void(hosted_match&)> started_;
    std::function<void(hosted_match&, const std::string&)> ending_;
};

}  // namespace arena::host
