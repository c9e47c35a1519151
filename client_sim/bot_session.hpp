#pragma once
// What the fleet drives, whatever carries the bytes: one simulated player's session. A TCP
// bot (bot.hpp) and a UDP bot (udp_bot.hpp) are two I/O adapters around the same client_core.
#include <boost/asio/awaitable.hpp>
#include <cstdint>
#include <string>

#include "client_sim/client_core.hpp"

namespace arena::bots {

class bot_session {
public:
    virtual ~bot_session() = default;
    // Connects, joins and plays until the session ends. Never throws.
    virtual boost::asio::awaitable<void> run() = 0;
    // One server tick passed: this tick's input, and a Ping once a second.
    virtual void on_tick(std::uint64_t tick, time_ns now) = 0;
    // The run is over: send Bye, close once it is written.
    virtual void finish() = 0;
    // Ends the session now, with this reason.
    virtual void abort(const std::string& reason) = 0;
    // Gives up when no Welcome came within the join timeout.
    virtual void check_join_timeout(time_ns now) = 0;
    [[nodiscard]] virtual bool ended() const = 0;
    [[nodiscard]] virtual const bot_outcome& outcome() const = 0;
    virtual void add_final_figures(fleet_metrics& metrics) const = 0;
};

}  // namespace arena::bots
