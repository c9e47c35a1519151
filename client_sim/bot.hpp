#pragma once
// One simulated player on one TCP connection: the socket adapter around a client_core. A
// reader coroutine feeds the core what the socket holds; a writer coroutine, the only one that
// writes to the socket, sends what the core queued and sleeps on a timer used as a wake-up
// while there is nothing (the shape of Asio's cpp20 chat_server example). Nothing here is
// timed per bot: the fleet's one shared ticker calls on_tick() for every bot once per server
// tick, so 1000 bots cost one timer, not 1000.
#include <boost/asio/awaitable.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "client_sim/bot_session.hpp"
#include "client_sim/client_core.hpp"

namespace arena::bots {

class fleet;

class bot : public bot_session {
public:
    bot(fleet& owner, client_params params);

    // Connects, joins and plays until the session ends. Never throws: whatever goes wrong
    // ends this bot's session only, with a reason.
    boost::asio::awaitable<void> run() override;

private:
    boost::asio::awaitable<void> reader();
    boost::asio::awaitable<void> writer();
    // After every call into the core: close the socket if it ended, else wake the writer if
    // it queued something.
    void sync() override;

    fleet& fleet_;
    bool slow_reader_;
    bool closed_ = false;

    boost::asio::ip::tcp::socket socket_;
    boost::asio::steady_timer wake_;  // the writer sleeps on it; sync() cancels it
    std::vector<std::uint8_t> read_buffer_;
    std::vector<std::uint8_t> sending_;  // frames being written; swapped with the core's output
};

}  // namespace arena::bots
