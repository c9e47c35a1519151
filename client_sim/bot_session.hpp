#pragma once
// What the fleet drives, whatever carries the bytes: one simulated player's session. A TCP bot
// (bot.hpp), a UDP bot (udp_bot.hpp) and a WebSocket bot (ws_bot.hpp) are I/O adapters around
// the same client_core: each runs its connection and, after every call into the core, moves
// what the core queued onto the wire (sync).
#include <boost/asio/awaitable.hpp>
#include <cstdint>
#include <string>
#include <utility>

#include "client_sim/client_core.hpp"

namespace arena::bots {

class bot_session {
public:
    virtual ~bot_session() = default;
    bot_session(const bot_session&) = delete;
    bot_session& operator=(const bot_session&) = delete;

    // Connects, joins and plays until the session ends. Never throws: whatever goes wrong ends
    // this bot's session only, with a reason.
    virtual boost::asio::awaitable<void> run() = 0;

    // One server tick passed: this tick's input, and a Ping once a second.
    void on_tick(std::uint64_t tick, time_ns now) {
        core_.on_tick(tick, now);
        sync();
    }
    // The run is over: send Bye, close once it is written.
    void finish() {
        core_.finish();
        sync();
    }
    // Ends the session now, with this reason.
    void abort(const std::string& reason) {
        core_.abort(reason);
        sync();
    }
    // Gives up when no Welcome came within the join timeout.
    void check_join_timeout(time_ns now) {
        core_.check_join_timeout(now);
        sync();
    }
    [[nodiscard]] bool ended() const { return core_.ended(); }
    [[nodiscard]] const bot_outcome& outcome() const { return core_.outcome(); }
    void add_final_figures(fleet_metrics& metrics) const { core_.add_final_figures(metrics); }

protected:
    bot_session(client_shared& shared, client_params params) : core_(shared, std::move(params)) {}

    // After every call into the core: the transport closes if the core ended, else sends (or
    // wakes its writer for) what the core queued.
    virtual void sync() = 0;

    client_core core_;
};

}  // namespace arena::bots
